use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/unknown_field.toml")]
struct Typo;

fn main() {}
