use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/good.toml")]
struct WithFields {
    speed: f64,
}

fn main() {}
