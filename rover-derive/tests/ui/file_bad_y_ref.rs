use rover_derive::Rover;

#[derive(Rover)]
#[rover(
    file = "../../../../rover-derive/tests/ui/good.toml",
    fidelity = "linearized",
    y_ref = [-0.3, 0.1]
)]
struct Frozen;

include!("../uses/use_all.rs");

fn main() {
    use_all!(Frozen, FrozenPlant, 7, 2);
}
