use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/no_such_rover.toml")]
struct Missing;

fn main() {}
