// Every item of a generated rover, used the way a user's code uses it:
// included by the cases in `ui/` (where the description is wrong and the
// derive emits its stub) and in `pass/` (where it is right), so that the
// stub is held to offer what a real plant offers, and a bad description
// to give its own error and nothing more. Every item of
// `rover_codegen::Item::ALL` is used here (`compile_fail.rs` checks it).
macro_rules! use_all {
    ($rover:ident, $plant:ident, $n:literal, $w:literal) => {{
        use rover_dynamics::described::Described;
        use rover_dynamics::nalgebra::SVector;
        use rover_dynamics::plant::{FixedPlant, Plant, WheelLoad};
        use rover_dynamics::wheel_ground::Search;
        use rover_runtime::RoverDescription;
        use rover_runtime::terrain::Flat;
        use rover_runtime::wheel_law::WheelLawConfig;
        use rover_scenario::Simulation;

        let mut plant: $plant = $rover::plant();
        let _ = $plant::new();
        let _ = (
            $plant::NAME,
            $plant::DOF,
            $plant::WHEELS,
            $plant::COORDINATES,
            $plant::WHEEL_NAMES,
            $plant::SPRING_NEUTRALS,
            $plant::MIN_COS_ROLL,
        );
        let _ = plant.spring_neutrals();
        let x = [0.0; $n];
        let loads = [WheelLoad::default(); $w];
        let (mut xd, mut wd) = ([0.0; $n], [0.0; $n]);
        let _ = plant.derivatives_array(&x, &x, &loads, &mut xd, &mut wd);
        let _ = plant.mass_matrix_array(&x)[0][0];
        let _ = plant.wheels_array(&x, &x, &[0.0; $w])[0].centre;
        let _ = plant.jacobian_array(&x, &x, &loads)[0][$n];
        let xs = SVector::<f64, $n>::zeros();
        let (mut xds, mut wds) = (xs, xs);
        let _ = plant.derivatives_fixed(&xs, &xs, &loads, &mut xds, &mut wds);
        let _ = plant.mass_matrix_fixed(&xs)[(0, 0)];
        let _ = plant.jacobian_fixed(&xs, &xs, &loads)[(0, $n)];
        let _ = plant.wheels_fixed(&xs, &xs, &SVector::<f64, $w>::zeros());
        let _ = plant.derivatives_portable(&x, &x, &loads, &mut xd, &mut wd);
        let _ = ($plant::TYRES, $plant::RADII);
        let mut ground = $plant::ground(Search::default());
        let _ = plant.derivatives_on_ground(
            &mut ground,
            &Flat::default(),
            &WheelLawConfig::default(),
            &$plant::TYRES,
            &x,
            &x,
            &[0.0; $w],
            |normals: &[f64; $w]| *normals,
            &mut xd,
            &mut wd,
        );
        let _ = plant.derivatives(&x, &x, &loads, &mut xd, &mut wd);
        fn slices<P: Plant>(_: &P) {}
        slices(&plant);
        fn fixed<P: FixedPlant<$n, $w>>(_: &P) {}
        fixed(&plant);
        fn default<P: Default>() -> P {
            P::default()
        }
        let _: $plant = default();
        let _ = ($rover::DESCRIPTION, <$plant as Described>::ORIGIN, $rover::FIDELITY);
        let _ = ($rover::report(), $rover::model(), $plant::spec());
        let _ = Simulation::new($rover::plant()).speed(0.1).run(0.0);
    }};
}
