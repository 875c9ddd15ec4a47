use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/good.toml", gravity = 9.81)]
struct Both;

include!("../uses/use_all.rs");

fn main() {
    use_all!(Both, BothPlant, 7, 2);
}
