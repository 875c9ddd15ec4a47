use rover_derive::Rover;

#[derive(Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/negative_mass.toml")]
struct NegativeMass;

include!("../uses/use_all.rs");

fn main() {
    use_all!(NegativeMass, NegativeMassPlant, 7, 2);
}
