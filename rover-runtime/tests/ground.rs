//! Wheel–ground interaction: static equilibrium on flat ground,
//! contact geometry over a bump, the two contact methods against each other.

use rover_dynamics::Model;
use rover_dynamics::contact::RimSampling;
use rover_dynamics::wheel_ground::ContactMethod;
use rover_integrate::{BdfConfig, Integrator, IntegratorConfig, OdeSystem};
use rover_runtime::GenericPlant;
use rover_runtime::control::{Controller, ControllerConfig};
use rover_runtime::ground::Ground;
use rover_runtime::sim::RoverSystem;
use rover_runtime::terrain::Terrain;
use rover_runtime::wheel_law::WheelLawConfig;
use rover_test_support::hand_models::{exomars, swing4};

/// Drop `model` on flat ground at Z = 0 and let it settle for `seconds`.
fn settle(model: &Model, seconds: f64) -> (RoverSystem<GenericPlant, Terrain>, Vec<f64>) {
    let n = model.dof();
    let plant = GenericPlant::new(model.clone()).unwrap();
    let ground = Ground::new(
        Terrain::default(),
        model,
        ContactMethod::Meridional,
        RimSampling::default(),
        WheelLawConfig::default(),
    );
    let control = Controller::new(ControllerConfig::default(), model, 0.0).unwrap();
    let mut sys = RoverSystem::new(plant, Some(ground), control);
    let mut y = vec![0.0; 2 * n + 1];
    let rest = model.rest();
    y[6..n].copy_from_slice(&rest);
    // Lowest wheel just touching.
    y[2] = model.touchdown_height();
    // Stiff: at standstill the regularized cornering law (v_ε = 1e-3 m/s) is
    // a lateral damper of C/v_ε = 5e4 N·s/m per wheel, so BDF, as the paper's ode15s.
    let mut integ = IntegratorConfig::Bdf(BdfConfig {
        rtol: 1e-6,
        atol: Some(1e-8),
        ..Default::default()
    })
    .build(2 * n + 1)
    .unwrap();
    let mut t = 0.0;
    integ.advance(&mut sys, &mut t, &mut y, seconds).unwrap();
    let mut dy = vec![0.0; 2 * n + 1];
    sys.rhs(t, &y, &mut dy).unwrap();
    let speed = y[n..2 * n].iter().fold(0.0f64, |a, v| a.max(v.abs()));
    assert!(
        speed < 1e-6,
        "not settled after {seconds} s: max |w| = {speed:e}"
    );
    (sys, y)
}

#[test]
fn paper_rovers_settle_to_static_equilibrium_on_flat_ground() {
    for (name, model) in [("exomars", exomars()), ("swing4", swing4())] {
        let (sys, y) = settle(&model, 30.0);
        let weight = model.total_mass() * model.gravity;
        let reports = sys.reports();
        let states = sys.wheel_states();
        let total: f64 = reports.iter().map(|r| r.normal).sum();
        assert!(
            (total - weight).abs() < 1e-6 * weight,
            "{name}: ΣF_n = {total} N, weight {weight} N"
        );
        // Front/rear split from the moment balance about G's y axis: the
        // normal forces at H_j balance the wheels' weights at G_j (the
        // body's weight acts at G).
        let (xg, mg) = (y[0], model.bodies[0].mass * model.gravity);
        let front: Vec<usize> = (0..states.len())
            .filter(|&k| states[k].centre[0] > xg)
            .collect();
        let rear: Vec<usize> = (0..states.len())
            .filter(|&k| states[k].centre[0] <= xg)
            .collect();
        let mean_x = |ks: &[usize]| {
            let f: f64 = ks.iter().map(|&k| reports[k].normal).sum();
            (
                f,
                ks.iter()
                    .map(|&k| reports[k].normal * (reports[k].point[0] - xg))
                    .sum::<f64>()
                    / f,
            )
        };
        let (f_front, x_front) = mean_x(&front);
        let (_, x_rear) = mean_x(&rear);
        let wheel_moment: f64 = states.iter().map(|s| mg * (s.centre[0] - xg)).sum();
        let expected_front = (wheel_moment - weight * x_rear) / (x_front - x_rear);
        assert!(
            (f_front - expected_front).abs() < 1e-6 * weight,
            "{name}: front axle carries {f_front} N, the moment balance gives {expected_front} N"
        );
        if name == "exomars" {
            // Free rockers with equal arms (±45°): on each side the front and
            // middle wheels carry the same load, and by symmetry so do the two
            // rear wheels. Every wheel carries about (m_B/6 + m_w)·g; not
            // exactly, because the paper's rounded geometry puts the rear
            // wheel centres 0.1 mm below the others (0.267·cos 48.5° vs
            // 0.250·cos 45°), which pitches the body by 3e-4 rad.
            let f: Vec<f64> = reports.iter().map(|r| r.normal).collect();
            assert!(
                (f[0] - f[2]).abs() < 1e-8 * f[0] && (f[1] - f[3]).abs() < 1e-8 * f[1],
                "rocker loads {f:?}"
            );
            assert!((f[4] - f[5]).abs() < 1e-8 * f[4], "rear loads {f:?}");
            let each = (model.body.mass / 6.0 + model.bodies[0].mass) * model.gravity;
            for (k, v) in f.iter().enumerate() {
                assert!(
                    (v - each).abs() < 1e-3 * each,
                    "exomars wheel {}: F_n = {v} N, expected about {each} N",
                    k + 1
                );
            }
        }
        for (k, (r, s)) in reports.iter().zip(states).enumerate() {
            let w = &model.wheels[k];
            let deflection = w.radius - (s.centre[2] - r.point[2]);
            assert!(
                (deflection - r.normal / w.stiffness).abs() < 1e-9,
                "{name}: wheel {} deflection {deflection} m vs F_n/k_w = {} m",
                k + 1,
                r.normal / w.stiffness
            );
        }
    }
}

#[test]
fn contact_follows_a_bump_and_both_methods_agree() {
    use rover_dynamics::HeightField;
    use rover_dynamics::contact::{MeridionalContact, TrackedContact};
    use rover_dynamics::plant::WheelState;
    use rover_runtime::terrain::TerrainConfig;
    // A raised-cosine ridge across X, 5 cm high and 0.6 m wide, at X = 1 m.
    let config: TerrainConfig =
        toml::from_str("kind = \"bump\"\nheight = 0.05\nwidth = 0.6\ncenter = [1.0, 0.0]").unwrap();
    let bump = config.build(std::path::Path::new(".")).unwrap();
    let radius = 0.09;
    let depth = 1e-4;
    let meridional = MeridionalContact::default();
    let mut tracked = TrackedContact::new(meridional);
    for k in 0..=60 {
        let xs = 0.6 + 0.8 * k as f64 / 60.0;
        // The surface point closest to a centre straight above: find the
        // centre height such that the wheel penetrates `depth` at its
        // closest approach, by bisection on the distance to the profile.
        let dist = |cx: f64, cz: f64| {
            (0..=4000)
                .map(|i| {
                    let x = cx - 0.2 + 0.4 * i as f64 / 4000.0;
                    let z = bump.height(x, 0.0).unwrap();
                    (((x - cx).powi(2) + (z - cz).powi(2)).sqrt(), x, z)
                })
                .fold(
                    (f64::INFINITY, 0.0, 0.0),
                    |a, b| if b.0 < a.0 { b } else { a },
                )
        };
        let (mut lo, mut hi) = (0.0, 0.5);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if dist(xs, mid).0 < radius - depth {
                lo = mid
            } else {
                hi = mid
            }
        }
        let cz = 0.5 * (lo + hi);
        let (_, px, pz) = dist(xs, cz);
        let state = WheelState {
            centre: [xs, 0.0, cz],
            velocity: [0.0; 3],
            spin_axis: [0.0, 1.0, 0.0],
        };
        let c = meridional
            .find(&bump, state.centre, state.spin_axis, radius)
            .unwrap();
        assert_eq!(c.count, 1, "one patch at x = {xs}");
        let p = c.patches[0];
        // The contact point is the closest surface point (to the chord's
        // sagitta, O(depth)), the normal points from it to the centre.
        assert!(
            (p.point[0] - px).abs() < 2e-3 && (p.point[2] - pz).abs() < 2e-3,
            "x = {xs}: H = {:?}, surface point ({px}, {pz})",
            p.point
        );
        let (nx, nz) = ((xs - px) / radius, (cz - pz) / radius);
        assert!(
            (p.normal[0] - nx).abs() < 0.03 && (p.normal[2] - nz).abs() < 0.03,
            "x = {xs}: n = {:?} vs ({nx}, {nz})",
            p.normal
        );
        // The model's own definition, computed by brute force: the rim's
        // crossings with the ground from 200 001 samples, H their midpoint,
        // Δ = R − |G_jH|.
        let rim = |b: f64| (xs + radius * b.sin(), cz - radius * b.cos());
        let below = |b: f64| {
            let (x, z) = rim(b);
            z < bump.height(x, 0.0).unwrap()
        };
        let betas: Vec<f64> = (0..=200_000)
            .map(|i| -1.5 + 3.0 * i as f64 / 200_000.0)
            .collect();
        let a = betas.iter().copied().find(|&b| below(b)).unwrap();
        let e = betas.iter().rev().copied().find(|&b| below(b)).unwrap();
        let (ra, re) = (rim(a), rim(e));
        let h = (0.5 * (ra.0 + re.0), 0.5 * (ra.1 + re.1));
        let expected = radius - ((xs - h.0).powi(2) + (cz - h.1).powi(2)).sqrt();
        assert!(
            (p.deflection - expected).abs() < 1e-7,
            "x = {xs}: deflection {} vs brute force {expected}",
            p.deflection
        );
        assert!(
            (p.point[0] - h.0).abs() < 1e-5 && (p.point[2] - h.1).abs() < 1e-5,
            "x = {xs}: H {:?} vs brute force {h:?}",
            p.point
        );
        // Tracking from the previous position gives the same patch.
        let t = tracked
            .find(&bump, state.centre, state.spin_axis, radius)
            .unwrap();
        assert_eq!(t.count, 1);
        // Normal forces (k_w·Δ) within 1 % (MODEL.md §6).
        let (a, b) = (t.patches[0].deflection, p.deflection);
        assert!(
            (a - b).abs() <= 0.01 * b,
            "x = {xs}: tracked Δ = {a} vs meridional {b}"
        );
    }
}

/// A terrain seen through a probe that counts height queries and, unless
/// `bounded`, hides the terrain's height bound: the contact search then
/// samples the whole half rim, as it did before the bound existed. Unless
/// `sloped`, it also hides the terrain's slope bound, with which the
/// search skips the samples that cannot change side from the last one.
struct Probe<'a> {
    terrain: &'a Terrain,
    bounded: bool,
    sloped: bool,
    queries: std::cell::Cell<usize>,
}

impl<'a> Probe<'a> {
    fn new(terrain: &'a Terrain, bounded: bool) -> Self {
        Probe {
            terrain,
            bounded,
            sloped: bounded,
            queries: std::cell::Cell::new(0),
        }
    }

    /// With the height bound and without the slope bound.
    fn height_bound_only(terrain: &'a Terrain) -> Self {
        Probe {
            sloped: false,
            ..Probe::new(terrain, true)
        }
    }
}

impl rover_dynamics::HeightField for Probe<'_> {
    fn height(&self, x: f64, y: f64) -> Result<f64, rover_dynamics::height_field::OffMap> {
        self.queries.set(self.queries.get() + 1);
        self.terrain.height(x, y)
    }
    fn height_gradient(
        &self,
        x: f64,
        y: f64,
    ) -> Result<(f64, [f64; 2]), rover_dynamics::height_field::OffMap> {
        self.queries.set(self.queries.get() + 1);
        self.terrain.height_gradient(x, y)
    }
    fn max_height_in(&self, area: &rover_dynamics::height_field::Bounds) -> Option<f64> {
        self.terrain.max_height_in(area).filter(|_| self.bounded)
    }
    fn max_slope_in(&self, area: &rover_dynamics::height_field::Bounds) -> Option<f64> {
        self.terrain.max_slope_in(area).filter(|_| self.sloped)
    }
}

/// The terrains of the library with their bounds: analytic kinds, a random
/// field (bicubic, error edge), and a bilinear clamped grid.
fn bounded_terrains() -> Vec<(&'static str, Terrain)> {
    use rover_runtime::terrain::{EdgePolicy, Grid, Interpolation, TerrainConfig};
    let config = |text: &str| -> Terrain {
        let c: TerrainConfig = toml::from_str(text).unwrap();
        c.build(std::path::Path::new(".")).unwrap()
    };
    let bumpy = |x: f64, y: f64| 0.03 * (7.0 * x).sin() * (5.0 * y).cos() + 0.01 * (23.0 * y).sin();
    vec![
        ("flat", Terrain::default()),
        (
            "slope",
            config("kind = \"slope\"\nangle_deg = 12.0\ndirection_deg = 30.0"),
        ),
        (
            "bump",
            config("kind = \"bump\"\nheight = 0.05\nwidth = 0.6\ncenter = [0.3, 0.0]"),
        ),
        (
            "ditch",
            config("kind = \"ditch\"\ndepth = 0.05\nwidth = 0.5\ncenter = [-0.4, 0.0]"),
        ),
        (
            "step",
            config("kind = \"step\"\nheight = 0.04\nposition = [0.2, 0.0]\nramp_width = 0.01"),
        ),
        (
            "sinusoid",
            config("kind = \"sinusoid\"\namplitude = 0.02\nwavelength = 0.7"),
        ),
        (
            // Crests closer than a wheel is wide: patches split over them.
            "corrugations",
            config(
                "kind = \"sinusoid\"\namplitude = 0.008\nwavelength = 0.09\ndirection_deg = 20.0",
            ),
        ),
        (
            "sharp step",
            config("kind = \"step\"\nheight = 0.03\nposition = [-0.3, 0.1]\ndirection_deg = 100.0"),
        ),
        (
            "random",
            config("kind = \"random\"\nz_r = 0.3\nseed = 7\nextent = [-2.0, 2.0, -2.0, 2.0]"),
        ),
        (
            "grid",
            Terrain::Grid(
                Grid::from_fn([-1.6, -1.6], [0.05, 0.04], 65, 81, bumpy)
                    .unwrap()
                    .with_interpolation(Interpolation::Bilinear)
                    .with_edge_policy(EdgePolicy::Clamp),
            ),
        ),
        (
            // Bicubic up to a clamped edge at X = 1.2 m, inside the trials'
            // area, so that wheels straddle the ghost nodes and the held edge.
            "bicubic clamped grid",
            Terrain::Grid(
                Grid::from_fn([-1.7, -1.7], [0.04, 0.05], 73, 69, bumpy)
                    .unwrap()
                    .with_edge_policy(EdgePolicy::Clamp),
            ),
        ),
    ]
}

#[test]
fn the_bounded_contact_search_is_the_full_search_bit_for_bit() {
    use rover_dynamics::HeightField;
    use rover_dynamics::contact::MeridionalContact;
    let mut rng = rover_test_support::rng::Rng::new(2026);
    let search = MeridionalContact::default();
    for (name, terrain) in bounded_terrains() {
        // All through the probe, which hides a plane's closed form (held
        // against the sampled search on its own below): sampling with both
        // bounds, with the height bound alone, and with none.
        let (culled, full) = (Probe::new(&terrain, true), Probe::new(&terrain, false));
        let unskipped = Probe::height_bound_only(&terrain);
        let (mut touching, mut split) = (0, 0);
        for trial in 0..400 {
            let (x, y) = (rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
            let radius = rng.uniform(0.08, 0.4);
            // From 3 cm clear to 10 cm deep, tilted up to 30° about X and Y.
            let depth = rng.uniform(-0.03, 0.1);
            let z = terrain.height(x, y).unwrap() + radius - depth;
            let (roll, yaw) = (rng.uniform(-0.5, 0.5), rng.uniform(-3.1, 3.1));
            let axis = [-yaw.sin() * roll.cos(), yaw.cos() * roll.cos(), roll.sin()];
            let bounded = search.find(&culled, [x, y, z], axis, radius);
            let sampled = search.find(&full, [x, y, z], axis, radius);
            assert_eq!(bounded, sampled, "{name}, trial {trial}");
            let height_only = search.find(&unskipped, [x, y, z], axis, radius);
            assert_eq!(
                height_only, sampled,
                "{name}, trial {trial}: height bound only"
            );
            touching += usize::from(matches!(bounded, Ok(c) if c.count > 0));
            split += usize::from(matches!(bounded, Ok(c) if c.count > 1));
        }
        assert!(
            touching > 200,
            "{name}: only {touching} of 400 wheels touch"
        );
        // The slope bound must save queries on every terrain.
        let (skipping, not) = (culled.queries.get(), unskipped.queries.get());
        println!("{name}: {skipping} queries with the slope bound, {not} without, {split} split");
        assert!(
            10 * skipping < 7 * not,
            "{name}: the slope bound saved too little ({skipping} against {not} queries)"
        );
    }
}

/// Where patches split, merge and are born beside each other (shallow
/// wheels on crests closer than a wheel is wide), the search that skips
/// samples by the slope bound still finds what sampling every one finds,
/// bit for bit: runs, dips between samples, ridges and the blend of a
/// split, whose scale depends on the depth of each run.
#[test]
fn skipping_samples_keeps_split_patches_bit_for_bit() {
    use rover_dynamics::HeightField;
    use rover_dynamics::contact::MeridionalContact;
    let mut rng = rover_test_support::rng::Rng::new(2027);
    let search = MeridionalContact::default();
    let (_, terrain) = bounded_terrains()
        .into_iter()
        .find(|(name, _)| *name == "corrugations")
        .unwrap();
    let (culled, full) = (Probe::new(&terrain, true), Probe::new(&terrain, false));
    let mut split = 0;
    for trial in 0..2000 {
        let (x, y) = (rng.uniform(-1.5, 1.5), rng.uniform(-1.5, 1.5));
        let radius = rng.uniform(0.08, 0.4);
        // From 2 mm clear to 1.2 cm deep: the crests' tops cross the rim.
        let depth = rng.uniform(-0.002, 0.012);
        let z = terrain.height(x, y).unwrap() + radius - depth;
        let (roll, yaw) = (rng.uniform(-0.3, 0.3), rng.uniform(-3.1, 3.1));
        let axis = [-yaw.sin() * roll.cos(), yaw.cos() * roll.cos(), roll.sin()];
        let skipping = search.find(&culled, [x, y, z], axis, radius).unwrap();
        let sampled = search.find(&full, [x, y, z], axis, radius).unwrap();
        assert_eq!(skipping, sampled, "trial {trial}");
        split += usize::from(sampled.count > 1);
    }
    assert!(
        split > 200,
        "only {split} of 2000 wheels have split patches"
    );
    assert!(
        2 * culled.queries.get() < full.queries.get(),
        "the slope bound saved too little ({} against {} queries)",
        culled.queries.get(),
        full.queries.get()
    );
}

#[test]
fn a_contact_found_in_place_forgets_the_previous_one() {
    use rover_dynamics::contact::{Contact, MeridionalContact};
    let search = MeridionalContact::default();
    // 5 cm high, 0.6 m wide, centred at X = 0.3 m.
    let (_, bump) = bounded_terrains()
        .into_iter()
        .find(|(name, _)| *name == "bump")
        .unwrap();
    let axis = [0.0, 1.0, 0.0];
    // A deep contact on the bump, then a wheel in the air, a shallow one on
    // flat ground and one on the bump's flank, each into the same value.
    let mut kept = search.find(&bump, [0.3, 0.0, 0.12], axis, 0.09).unwrap();
    assert!(kept.count > 0);
    for centre in [[3.0, 0.0, 0.5], [3.0, 0.0, 0.089], [0.5, 0.0, 0.1]] {
        search
            .find_into(&bump, centre, axis, 0.09, &mut kept)
            .unwrap();
        assert_eq!(kept, search.find(&bump, centre, axis, 0.09).unwrap());
    }
    assert_ne!(kept, Contact::default());
}

#[test]
fn a_wheel_on_flat_ground_samples_only_the_rim_near_the_ground() {
    use rover_dynamics::contact::MeridionalContact;
    let flat = Terrain::default();
    let search = MeridionalContact::default();
    // 2 mm into the ground, as a rover at rest: the rim within 2.2 mm of the
    // ground is 2·7.5° of the 180° sampled.
    let (culled, full) = (Probe::new(&flat, true), Probe::new(&flat, false));
    let centre = [0.0, 0.0, 0.25 - 2e-3];
    let a = search.find(&culled, centre, [0.0, 1.0, 0.0], 0.25).unwrap();
    let b = search.find(&full, centre, [0.0, 1.0, 0.0], 0.25).unwrap();
    assert_eq!(a, b);
    assert_eq!(a.count, 1);
    let (used, all) = (culled.queries.get(), full.queries.get());
    assert!(
        all >= 181,
        "the full search samples the whole half rim ({all})"
    );
    assert!(
        used < 50,
        "the bounded search evaluated {used} heights (full: {all})"
    );
}

/// A rectangle of up to 0.8 m × 0.8 m around the trials' area.
fn random_area(rng: &mut rover_test_support::rng::Rng) -> rover_dynamics::height_field::Bounds {
    let (x, y) = (rng.uniform(-1.8, 1.6), rng.uniform(-1.8, 1.6));
    let (w, h) = (rng.uniform(0.0, 0.8), rng.uniform(0.0, 0.8));
    rover_dynamics::height_field::Bounds {
        x_min: x,
        x_max: x + w,
        y_min: y,
        y_max: y + h,
    }
}

/// The slope bound of every terrain holds at random points of random
/// rectangles (including rectangles across a grid's clamped edge and a
/// step's ramp), and is `None` for a non-finite rectangle.
#[test]
fn terrain_slope_bounds_hold() {
    use rover_dynamics::height_field::{Bounds, HeightField};
    let mut rng = rover_test_support::rng::Rng::new(78);
    for (name, terrain) in bounded_terrains() {
        let mut bounded = 0;
        for _ in 0..300 {
            let area = random_area(&mut rng);
            let Some(steepest) = terrain.max_slope_in(&area) else {
                continue;
            };
            bounded += 1;
            for _ in 0..50 {
                let (px, py) = (
                    rng.uniform(area.x_min, area.x_max),
                    rng.uniform(area.y_min, area.y_max),
                );
                let (_, [gx, gy]) = terrain.height_gradient(px, py).unwrap();
                assert!(
                    gx.hypot(gy) <= steepest,
                    "{name}: slope {} above its bound {steepest} in {area:?}",
                    gx.hypot(gy)
                );
            }
        }
        assert!(bounded > 100, "{name}: only {bounded} areas bounded");
        let nan = Bounds {
            x_min: f64::NAN,
            ..random_area(&mut rng)
        };
        assert_eq!(terrain.max_slope_in(&nan), None, "{name}: NaN area");
    }
}

#[test]
fn terrain_height_bounds_hold() {
    use rover_dynamics::height_field::{Bounds, HeightField};
    let mut rng = rover_test_support::rng::Rng::new(77);
    for (name, terrain) in bounded_terrains() {
        for _ in 0..300 {
            let area = random_area(&mut rng);
            let Some(top) = terrain.max_height_in(&area) else {
                continue;
            };
            for _ in 0..50 {
                let (px, py) = (
                    rng.uniform(area.x_min, area.x_max),
                    rng.uniform(area.y_min, area.y_max),
                );
                let z = terrain.height(px, py).unwrap();
                assert!(
                    z <= top + 1e-12,
                    "{name}: {z} above its bound {top} in {area:?}"
                );
            }
        }
        let nan = Bounds {
            x_min: f64::NAN,
            ..random_area(&mut rng)
        };
        assert_eq!(terrain.max_height_in(&nan), None, "{name}: NaN area");
    }
}

/// A 13 cm wheel, level and across X, lowered from centre height `top` by
/// `steps` steps of `dz` at X = `x`: the patch count at every height and
/// the largest change of the summed deflection from one height to the next.
fn lowered(
    ground: &rover_runtime::terrain::Sinusoid,
    x: f64,
    top: f64,
    dz: f64,
    steps: usize,
) -> (Vec<usize>, f64) {
    let search = rover_dynamics::contact::MeridionalContact::default();
    let (mut counts, mut worst, mut prev) = (Vec::new(), 0.0_f64, None::<f64>);
    for k in 0..=steps {
        let z = top - k as f64 * dz;
        let c = search
            .find(ground, [x, 0.0, z], [0.0, 1.0, 0.0], 0.13)
            .unwrap();
        counts.push(c.count);
        let total: f64 = c.patches().iter().map(|p| p.deflection).sum();
        if let Some(p) = prev {
            worst = worst.max((total - p).abs());
        }
        prev = Some(total);
    }
    (counts, worst)
}

#[test]
fn a_patch_splitting_over_a_ridge_hands_over_its_force_continuously() {
    use rover_runtime::terrain::Sinusoid;
    // Crests at X = ±3 cm, a trough at X = 0: a 13 cm wheel lowered over
    // the trough touches both crests (two patches), then the rim reaches
    // the trough and the two become one (at a centre height of 0.12 m).
    // The paper's chord law alone makes the summed deflection, hence the
    // normal force, jump there by about 3 mm (a rover can come to rest on
    // that jump, where no implicit integrator converges); the split is
    // blended in over the ridge's clearance instead.
    let ground = Sinusoid::new(0.01, 0.06, 0.0, -90.0).unwrap();
    let dz = 1e-5;
    for x in [0.0, 0.0011] {
        let (counts, worst) = lowered(&ground, x, 0.125, dz, 1000);
        assert!(
            counts.contains(&1) && counts.iter().any(|&c| c >= 2),
            "x = {x}: the scan must cross the split"
        );
        // Away from the split the sum moves by at most ~2·dz per step; the
        // blend adds about 3 mm over 1 mm of height (3·dz); a jump is 3 mm.
        assert!(
            worst < 10.0 * dz,
            "x = {x}: summed deflection jumps by {worst:e} m"
        );
    }
}

#[test]
fn patches_born_beside_a_patch_over_shallow_troughs_appear_continuously() {
    use rover_runtime::terrain::Sinusoid;
    // Ripples 2 cm apart and 0.8 mm deep, more curved than the rim: as the
    // wheel sinks, patches are born on the crests beside the first one,
    // across troughs that clear the rim by less than the split band, and
    // later merge over them. A patch born half-merged with its neighbour
    // would make the summed deflection jump.
    let ground = Sinusoid::new(0.0004, 0.02, 0.0, -90.0).unwrap();
    let dz = 1e-7;
    for x in [0.0013, 0.0031] {
        let (counts, worst) = lowered(&ground, x, 0.1305, dz, 20_000);
        let births = counts
            .windows(2)
            .filter(|c| c[0] > 0 && c[1] > c[0])
            .count();
        assert!(births >= 1, "x = {x}: a patch must be born beside another");
        assert!(
            worst < 10.0 * dz,
            "x = {x}: summed deflection jumps by {worst:e} m"
        );
    }
}

#[test]
fn a_wheel_buried_to_its_centre_pulls_continuously_in_its_drive_torque() {
    use rover_dynamics::contact::{Contact, Patch};
    use rover_dynamics::plant::WheelState;
    use rover_dynamics::wheel_ground::wheel_load;
    use rover_dynamics::wheel_law::Tyre;
    use rover_runtime::wheel_law::ChenGenta;
    // The chord of a wheel buried to its centre passes through G_j: eq. 38's
    // F_d = τ/|G_jH| would saturate at ±μx·F_n for any torque, flipping
    // sign with it. With the lever floored at R/2 the pull is 2τ/R.
    let radius = 0.13;
    let patch = Patch {
        point: [0.0, 0.0, 0.0],
        normal: [0.0, 0.0, 1.0],
        tangent: [1.0, 0.0, 0.0],
        lateral: [0.0, 1.0, 0.0],
        deflection: radius,
        lever: 0.0,
        angle: 0.0,
    };
    let mut contact = Contact::default();
    contact.patches[0] = patch;
    contact.count = 1;
    let tyre = Tyre {
        stiffness: 5e4,
        damping: 500.0,
        mu_x: 0.5,
        mu_y: 0.5,
        cornering_stiffness: 1e3,
        rolling_resistance: 0.0,
    };
    let state = WheelState {
        centre: [0.0, 0.0, 0.0],
        velocity: [0.0; 3],
        spin_axis: [0.0, 1.0, 0.0],
    };
    let lever = 0.5 * radius;
    for torque in [-1e-9, 0.0, 1e-9, 0.5, -0.5] {
        let (_, report) = wheel_load(&ChenGenta::default(), &tyre, &state, &contact, torque);
        assert!(
            (report.drawbar - torque / lever).abs() <= 1e-12,
            "τ = {torque}: F_d = {}",
            report.drawbar
        );
        // The motor reacts with the torque that drives the pull.
        assert!((report.torque - torque).abs() <= 1e-12, "{}", report.torque);
    }
}

#[test]
fn a_plane_cuts_the_rim_in_closed_form_where_the_sampled_search_finds_it() {
    use rover_dynamics::HeightField;
    use rover_dynamics::contact::{MeridionalContact, TrackedContact};
    use rover_runtime::terrain::TerrainConfig;
    let config = |text: &str| -> Terrain {
        let c: TerrainConfig = toml::from_str(text).unwrap();
        c.build(std::path::Path::new(".")).unwrap()
    };
    let planes = [
        ("flat", config("kind = \"flat\"\nheight = 0.37")),
        (
            "slope",
            config("kind = \"slope\"\nangle_deg = 12.0\ndirection_deg = 30.0"),
        ),
        (
            "steep",
            config("kind = \"slope\"\nangle_deg = -35.0\ndirection_deg = 200.0\nheight = -1.0"),
        ),
    ];
    let mut rng = rover_test_support::rng::Rng::new(77);
    let search = MeridionalContact::default();
    let (mut worst_deflection, mut worst_point) = (0.0f64, 0.0f64);
    for (name, terrain) in &planes {
        // Its heights are the plane's, bit for bit.
        let plane = terrain.plane().expect("a plane");
        // The probe hides the plane: the sampled search.
        let sampled_ground = Probe::new(terrain, true);
        let (mut touching, mut deep) = (0, 0);
        for trial in 0..1000 {
            let (x, y) = (rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0));
            assert_eq!(
                terrain.height(x, y).unwrap().to_bits(),
                plane.height_at(x, y).to_bits()
            );
            let radius = rng.uniform(0.08, 0.4);
            // From 3 cm clear to 7 cm deep (past the centre of the smallest
            // wheels: the sampled search then takes over), tilted up to 30°.
            let z = terrain.height(x, y).unwrap() + radius - rng.uniform(-0.03, 0.07);
            let (roll, yaw) = (rng.uniform(-0.5, 0.5), rng.uniform(-3.1, 3.1));
            let axis = [-yaw.sin() * roll.cos(), yaw.cos() * roll.cos(), roll.sin()];
            let cut = search.find(terrain, [x, y, z], axis, radius).unwrap();
            // The tracked search, even with a contact to track from, takes
            // the same cut on a plane (it keeps the deepest patch only, so
            // compare where the cut has one).
            let mut tracked = TrackedContact::new(search);
            tracked.find(terrain, [x, y, z], axis, radius).unwrap();
            let again = tracked.find(terrain, [x, y, z], axis, radius).unwrap();
            if cut.count <= 1 {
                assert_eq!(again, cut, "{name}, trial {trial}: tracked");
            }
            let sampled = search
                .find(&sampled_ground, [x, y, z], axis, radius)
                .unwrap();
            assert_eq!(cut.count, sampled.count, "{name}, trial {trial}");
            assert_eq!(cut.deep, sampled.deep, "{name}, trial {trial}");
            for (p, q) in cut.patches().iter().zip(sampled.patches()) {
                let gap = |a: [f64; 3], b: [f64; 3]| {
                    (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max)
                };
                worst_deflection = worst_deflection.max((p.deflection - q.deflection).abs());
                worst_point = worst_point.max(gap(p.point, q.point));
                // The sampled ends have a height residual of at most 1e-9 m
                // (RimSampling::tolerance): the deflections agree to that.
                assert!(
                    (p.deflection - q.deflection).abs() <= 2e-9,
                    "{name}, trial {trial}: deflection {} vs {}",
                    p.deflection,
                    q.deflection
                );
                assert!(gap(p.normal, q.normal) < 1e-6, "{name}, trial {trial}");
                assert!(gap(p.point, q.point) < 1e-6, "{name}, trial {trial}");
                assert!(gap(p.tangent, q.tangent) < 1e-6, "{name}, trial {trial}");
                assert!(gap(p.lateral, q.lateral) < 1e-6, "{name}, trial {trial}");
                assert!((p.lever - q.lever).abs() <= 2e-9, "{name}, trial {trial}");
                assert!((p.angle - q.angle).abs() < 1e-6, "{name}, trial {trial}");
            }
            touching += usize::from(cut.count > 0);
            deep += usize::from(cut.deep);
        }
        assert!(
            touching > 500,
            "{name}: only {touching} of 1000 wheels touch"
        );
        // On flat ground the half rim's ends are level with the centre, so
        // only a wheel buried past it reaches them (the sampled search's
        // case); on a slope the downhill end dips below sooner.
        if *name == "steep" {
            assert!(deep > 10, "{name}: {deep} wheels reached a half-rim end");
        }
    }
    eprintln!("closed form vs sampled: deflection {worst_deflection:e} m, point {worst_point:e} m");
}
