use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/good.toml")]
struct WithFields {
    speed: f64,
}

include!("../uses/use_all.rs");

fn main() {
    use_all!(WithFields, WithFieldsPlant, 7, 2);
}
