//! The bounded contact search against a dense reference: 3,601 rim samples
//! (0.05° apart) with crossings refined to 1e-12 m, on 12,000 seeded wheel
//! poses over the paper's random field at Z_R = 0.2 and 1.0, a random field
//! with its flat start patch, a bump, a ditch and a 20° slope. Same patches, points and deflections to 1e-6 m, normal
//! forces to 1e-4 of the wheel's load; the 181-sample search, held against
//! the same reference, shows what it misses.

use rover_dynamics::contact::{BoundedContact, Contact, MeridionalContact, RimSampling};
use rover_dynamics::height_field::{Bounds, HeightField, OffMap, Plane};
use rover_terrain::{Terrain, TerrainConfig};
use rover_test_support::rng::Rng;

/// A terrain seen through a probe that counts queries and can hide the
/// plane (so that the reference samples a slope instead of cutting it in
/// closed form).
struct Probe<'a> {
    terrain: &'a Terrain,
    plane: bool,
    queries: std::cell::Cell<usize>,
}

impl<'a> Probe<'a> {
    fn new(terrain: &'a Terrain, plane: bool) -> Self {
        Probe {
            terrain,
            plane,
            queries: std::cell::Cell::new(0),
        }
    }
}

impl HeightField for Probe<'_> {
    fn height(&self, x: f64, y: f64) -> Result<f64, OffMap> {
        self.queries.set(self.queries.get() + 1);
        self.terrain.height(x, y)
    }
    fn height_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), OffMap> {
        self.queries.set(self.queries.get() + 1);
        self.terrain.height_gradient(x, y)
    }
    fn max_height_in(&self, area: &Bounds) -> Option<f64> {
        self.terrain.max_height_in(area)
    }
    fn max_slope_in(&self, area: &Bounds) -> Option<f64> {
        self.terrain.max_slope_in(area)
    }
    fn max_curvature_in(&self, area: &Bounds) -> Option<f64> {
        self.terrain.max_curvature_in(area)
    }
    fn plane(&self) -> Option<Plane> {
        self.terrain.plane().filter(|_| self.plane)
    }
}

fn terrain(text: &str) -> Terrain {
    let c: TerrainConfig = toml::from_str(text).unwrap();
    c.build(std::path::Path::new(".")).unwrap()
}

/// The terrains of the contract, with the area the wheels are put on.
fn terrains() -> Vec<(&'static str, Terrain, [f64; 4])> {
    let random = |z_r: f64| {
        terrain(&format!(
            "kind = \"random\"\nz_r = {z_r}\nseed = 3\nnode_amplitude = 0.25\n\
             extent = [-3.0, 3.0, -3.0, 3.0]\npatch_radius = 0.0\npatch_blend = 0.0"
        ))
    };
    vec![
        ("random Z_R = 0.2", random(0.2), [-2.5, 2.5, -2.5, 2.5]),
        ("random Z_R = 1.0", random(1.0), [-2.5, 2.5, -2.5, 2.5]),
        (
            // Wheels on the flat start patch (a plane under them), on its
            // blend ring, and beyond.
            "random with its flat start patch",
            terrain(
                "kind = \"random\"\nz_r = 0.5\nseed = 4\nnode_amplitude = 0.25\n\
                 extent = [-3.0, 3.0, -3.0, 3.0]\npatch_radius = 0.6\npatch_blend = 0.5",
            ),
            [-1.2, 1.2, -1.2, 1.2],
        ),
        (
            "bump",
            terrain(
                "kind = \"bump\"\nheight = 0.08\nwidth = 0.5\ntop_width = 0.1\ncenter = [0.0, 0.0]",
            ),
            [-0.45, 0.45, -0.45, 0.45],
        ),
        (
            "ditch",
            terrain(
                "kind = \"ditch\"\ndepth = 0.1\nwidth = 0.5\nbottom_width = 0.1\ncenter = [0.0, 0.0]",
            ),
            [-0.45, 0.45, -0.45, 0.45],
        ),
        (
            "slope 20°",
            terrain("kind = \"slope\"\nangle_deg = 20.0\ndirection_deg = 30.0"),
            [-1.0, 1.0, -1.0, 1.0],
        ),
    ]
}

/// A wheel pose: centre, unit spin axis, radius; from 2 cm clear to 5 cm
/// deep at its centre's vertical, tilted up to 20° about any horizontal axis.
fn pose(rng: &mut Rng, t: &Terrain, area: [f64; 4]) -> ([f64; 3], [f64; 3], f64) {
    let (x, y) = (rng.uniform(area[0], area[1]), rng.uniform(area[2], area[3]));
    let radius = rng.uniform(0.08, 0.4);
    let depth = rng.uniform(-0.02, 0.05);
    let z = t.height(x, y).unwrap() + radius - depth;
    let (roll, yaw) = (rng.uniform(-0.35, 0.35), rng.uniform(-3.1, 3.1));
    let axis = [-yaw.sin() * roll.cos(), yaw.cos() * roll.cos(), roll.sin()];
    ([x, y, z], axis, radius)
}

/// Tyre stiffness for the force comparison [N/m] (the paper's rovers: 1e4–1e5).
const K_W: f64 = 3e4;

/// Largest differences of `c` from `reference`: patch point, deflection
/// [m], and the normal force `k_w·Δ` summed over the wheel's patches, as a
/// fraction of the larger of the two sums (floored at 1 N, a wheel barely
/// touching).
fn differences(c: &Contact, reference: &Contact) -> (f64, f64, f64) {
    let (mut point, mut deflection) = (0.0f64, 0.0f64);
    for (p, q) in c.patches().iter().zip(reference.patches()) {
        let d = (0..3)
            .map(|k| (p.point[k] - q.point[k]).abs())
            .fold(0.0, f64::max);
        point = point.max(d);
        deflection = deflection.max((p.deflection - q.deflection).abs());
    }
    let load = |c: &Contact| c.patches().iter().map(|p| K_W * p.deflection).sum::<f64>();
    let (a, b) = (load(c), load(reference));
    (point, deflection, (a - b).abs() / a.max(b).max(1.0))
}

#[test]
fn the_bounded_search_finds_the_dense_reference_patches() {
    let reference_search = MeridionalContact {
        sampling: RimSampling {
            samples: 3601,
            tolerance: 1e-12,
        },
    };
    let bounded = BoundedContact::default();
    let sampled = MeridionalContact::default();
    let mut rng = Rng::new(0x00c0_47ac_7000);
    let mut total = 0;
    for (name, t, area) in terrains() {
        let dense = Probe::new(&t, false);
        let (fast, old) = (Probe::new(&t, true), Probe::new(&t, true));
        let (mut worst, mut worst_old) = ((0.0f64, 0.0f64, 0.0f64), (0.0f64, 0.0f64, 0.0f64));
        let (mut touching, mut split, mut old_miscounts) = (0, 0, 0);
        for trial in 0..2000 {
            let (centre, axis, radius) = pose(&mut rng, &t, area);
            let reference = reference_search.find(&dense, centre, axis, radius).unwrap();
            let found = bounded.find(&fast, centre, axis, radius).unwrap();
            assert_eq!(
                found.count, reference.count,
                "{name}, trial {trial}: {found:?}\nagainst the reference\n{reference:?}"
            );
            assert_eq!(found.deep, reference.deep, "{name}, trial {trial}");
            let d = differences(&found, &reference);
            assert!(
                d.0 < 1e-6 && d.1 < 1e-6 && d.2 < 1e-4,
                "{name}, trial {trial}: point {:.2e} m, deflection {:.2e} m, normal force {:.2e}",
                d.0,
                d.1,
                d.2
            );
            worst = (worst.0.max(d.0), worst.1.max(d.1), worst.2.max(d.2));
            let before = sampled.find(&old, centre, axis, radius).unwrap();
            if before.count == reference.count {
                let d = differences(&before, &reference);
                worst_old = (
                    worst_old.0.max(d.0),
                    worst_old.1.max(d.1),
                    worst_old.2.max(d.2),
                );
            } else {
                old_miscounts += 1;
            }
            touching += usize::from(reference.count > 0);
            split += usize::from(reference.count > 1);
            total += 1;
        }
        println!(
            "{name}: {touching} touching, {split} split; bounded search: point {:.1e} m, \
             deflection {:.1e} m, force {:.1e}, {:.1} queries a wheel; 181 samples: point \
             {:.1e} m, deflection {:.1e} m, force {:.1e}, {old_miscounts} patch counts wrong, \
             {:.1} queries a wheel",
            worst.0,
            worst.1,
            worst.2,
            fast.queries.get() as f64 / 2000.0,
            worst_old.0,
            worst_old.1,
            worst_old.2,
            old.queries.get() as f64 / 2000.0,
        );
        assert!(
            touching > 1000,
            "{name}: only {touching} of 2000 wheels touch"
        );
    }
    assert_eq!(total, 12_000);
}

/// A wheel moving in small steps, as an integrator's evaluations move it:
/// the search that keeps its memory between calls (bounds of its lattice
/// square, the last full search's certificate) finds the patches a fresh
/// search finds, to the crossings' rounding, with fewer terrain queries.
#[test]
fn a_search_that_remembers_finds_what_a_fresh_search_finds() {
    use rover_dynamics::contact::SearchMemory;
    let search = BoundedContact::default();
    let mut rng = Rng::new(0x0de7_0c47);
    for (name, t, area) in terrains() {
        let (remembering, fresh) = (Probe::new(&t, true), Probe::new(&t, true));
        let mut compared = 0;
        for walk in 0..40 {
            let (mut centre, mut axis, radius) = pose(&mut rng, &t, area);
            let mut memory = SearchMemory::default();
            for step in 0..50 {
                // As an implicit integrator moves it: evaluations within a
                // step (Newton iterations, a Jacobian's differences) up to
                // 10 µm apart, steps of up to 0.5 mm every fifth, and now
                // and then 5 mm.
                let scale = match step % 25 {
                    24 => 5e-3,
                    s if s % 5 == 4 => 5e-4,
                    _ => 1e-5,
                };
                for c in &mut centre {
                    *c += rng.uniform(-scale, scale);
                }
                let tilt = rng.uniform(-scale, scale);
                axis = [axis[0] - tilt * axis[2], axis[1], axis[2] + tilt * axis[0]];
                let n = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
                axis = axis.map(|a| a / n);
                let mut kept = Contact::default();
                search
                    .find_with(&remembering, centre, axis, radius, &mut memory, &mut kept)
                    .unwrap();
                let new = search.find(&fresh, centre, axis, radius).unwrap();
                assert_eq!(kept.count, new.count, "{name}, walk {walk}, step {step}");
                assert_eq!(kept.deep, new.deep, "{name}, walk {walk}, step {step}");
                let d = differences(&kept, &new);
                assert!(
                    d.0 < 1e-9 && d.1 < 1e-10,
                    "{name}, walk {walk}, step {step}: point {:.1e} m, deflection {:.1e} m",
                    d.0,
                    d.1
                );
                compared += usize::from(new.count > 0);
            }
        }
        let (kept, new) = (remembering.queries.get(), fresh.queries.get());
        println!("{name}: {compared} contacts, {kept} queries remembering, {new} fresh");
        assert!(compared > 500, "{name}: only {compared} contacts");
        assert!(
            name.starts_with("slope") || 2 * kept < new,
            "{name}: the memory saved too little ({kept} against {new} queries)"
        );
    }
}

/// The same walks as above, each wheel's search once on the terrain itself
/// (its bicubic cells kept between queries, `KeptCells`) and once through
/// a probe that hides them (every query the grid's own): the same patches
/// bit for bit, and the same number of terrain queries. A memory taken to
/// another terrain forgets what it learnt on the first: it finds what a
/// fresh memory finds there, bit for bit.
#[test]
fn kept_cells_change_no_bit_of_the_contact() {
    use rover_dynamics::contact::SearchMemory;
    let search = BoundedContact::default();
    let bits = |c: &Contact| {
        c.patches()
            .iter()
            .flat_map(|p| {
                let mut v = p.point.map(f64::to_bits).to_vec();
                v.extend(p.normal.map(f64::to_bits));
                v.push(p.deflection.to_bits());
                v
            })
            .collect::<Vec<_>>()
    };
    let mut rng = Rng::new(0x6e11_5eed);
    let mut grids = 0;
    for (name, t, area) in terrains() {
        if !matches!(t, Terrain::Grid(_)) {
            continue;
        }
        grids += 1;
        let hidden = Probe::new(&t, true);
        let mut compared = 0;
        for walk in 0..20 {
            let (mut centre, axis, radius) = pose(&mut rng, &t, area);
            let (mut kept, mut plain) = (SearchMemory::default(), SearchMemory::default());
            for step in 0..50 {
                // Steps of 0.1 mm, a 2 cm jump every tenth (across cells).
                let scale = if step % 10 == 9 { 2e-2 } else { 1e-4 };
                centre[0] += rng.uniform(0.0, scale);
                centre[1] += rng.uniform(-scale, scale);
                centre[2] += rng.uniform(-0.1, 0.1) * scale;
                let (mut a, mut b) = (Contact::default(), Contact::default());
                search
                    .find_with(&t, centre, axis, radius, &mut kept, &mut a)
                    .unwrap();
                search
                    .find_with(&hidden, centre, axis, radius, &mut plain, &mut b)
                    .unwrap();
                assert_eq!(
                    (a.count, a.deep, bits(&a)),
                    (b.count, b.deep, bits(&b)),
                    "{name}, walk {walk}, step {step}"
                );
                compared += usize::from(a.count > 0);
            }
        }
        assert!(compared > 300, "{name}: only {compared} contacts");
    }
    assert!(grids >= 2);

    // A memory taken from one grid to another.
    let (first, second) = (
        terrain("kind = \"random\"\nz_r = 0.2\nseed = 1\nextent = [-3.0, 3.0, -3.0, 3.0]"),
        terrain("kind = \"random\"\nz_r = 0.2\nseed = 2\nextent = [-3.0, 3.0, -3.0, 3.0]"),
    );
    let axis = [0.0, 1.0, 0.0];
    let mut moved = 0;
    for k in 0..200 {
        let x = -1.0 + 0.01 * f64::from(k);
        let top = first
            .height(x, 0.5)
            .unwrap()
            .max(second.height(x, 0.5).unwrap());
        let centre = [x, 0.5, top + 0.2 - 0.01];
        let mut memory = SearchMemory::default();
        let mut contact = Contact::default();
        search
            .find_with(&first, centre, axis, 0.2, &mut memory, &mut contact)
            .unwrap();
        search
            .find_with(&second, centre, axis, 0.2, &mut memory, &mut contact)
            .unwrap();
        let fresh = search.find(&second, centre, axis, 0.2).unwrap();
        assert_eq!(
            (contact.count, bits(&contact)),
            (fresh.count, bits(&fresh)),
            "x = {x}"
        );
        moved += usize::from(fresh.count > 0);
    }
    assert!(moved > 100, "only {moved} contacts");
}
