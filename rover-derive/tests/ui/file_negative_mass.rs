use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/negative_mass.toml")]
struct NegativeMass;

fn main() {}
