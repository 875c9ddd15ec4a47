use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/good.toml", gravity = 9.81)]
struct Both;

fn main() {}
