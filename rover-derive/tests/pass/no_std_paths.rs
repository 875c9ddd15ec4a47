// `no_std = true`: the generated code names `rover_dynamics` and `libm`
// directly, as firmware depending on them rather than on rover-runtime
// builds it.
use rover_dynamics::plant::Plant;

#[derive(rover_derive::Rover)]
#[rover(file = "../../../../rover-derive/tests/ui/good.toml", no_std = true)]
struct Firmware;

fn main() {
    let plant = Firmware::plant();
    assert_eq!(plant.dof(), 7);
    assert_eq!(FirmwarePlant::WHEELS, 1);
}
