use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/no_such_rover.toml")]
struct Missing;

include!("../uses/use_all.rs");

fn main() {
    use_all!(Missing, MissingPlant, 7, 2);
}
