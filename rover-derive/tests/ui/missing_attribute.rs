use rover_derive::Rover;

#[derive(Rover)]
struct NoDescription;

fn main() {}
