//! Soils by region in a scenario's `[terrain]`: a raster of classes and
//! patches over a background soil, each reference a name, a file or a
//! table; and the errors of each, naming the key.

use std::path::{Path, PathBuf};

use rover_runtime::soil::SoilConfig;
use rover_scenario::ground::{GroundConfig, SoilLayout};
use rover_scenario::scenario::Scenario;
use rover_terrain::SoilWeights;

/// A scratch directory of its own for each test.
fn dir(name: &str) -> PathBuf {
    let d = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("soil_map")
        .join(name);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn parse(text: &str) -> Result<Scenario, String> {
    Scenario::parse(&format!("duration = 1.0\n{text}"), Path::new("s.toml")).map_err(|e| e.message)
}

fn layout(ground: &GroundConfig, base: &Path) -> Result<Option<SoilLayout>, String> {
    let terrain = ground.build(base).map_err(|e| e.to_string())?;
    ground
        .soil_layout(base, &terrain)
        .map_err(|e| e.to_string())
}

fn layout_of(text: &str, base: &Path) -> Result<Option<SoilLayout>, String> {
    layout(&parse(text)?.terrain, base)
}

fn builtin(name: &str) -> rover_dynamics::soil::Soil {
    SoilConfig::builtin(name).unwrap().soil().unwrap()
}

/// 3 × 3 nodes 1 m apart from (−1, −1): class 1 in the middle, 2 at the
/// north-east corner, 0 elsewhere.
const CLASSES_CSV: &str = "# soil classes\nx0,y0,dx,dy\n-1,-1,1,1\n0,0,0\n0,1,0\n0,0,2\n";

const SOFT_TABLE: &str = "{ n = 1.0, k_c = 1400.0, k_phi = 820000.0, cohesion = 170.0, \
                          friction_angle_deg = 35.0, shear_modulus = 0.018 }";

#[test]
fn a_raster_and_patches_over_a_background_make_one_list_of_soils_and_a_map() {
    let base = dir("full");
    std::fs::write(base.join("classes.csv"), CLASSES_CSV).unwrap();
    std::fs::write(
        base.join("mud.toml"),
        "[soil]\nn = 0.8\nk_c = 5790.0\nk_phi = 180000.0\ncohesion = 300.0\nfriction_angle_deg = 17.8\nshear_modulus = 0.01\n",
    )
    .unwrap();
    let text = format!(
        "[terrain]\nkind = \"flat\"\nsoil = \"lunar_nominal\"\n\
         [terrain.soil_map]\npath = \"classes.csv\"\n\
         [terrain.soil_map.classes]\n0 = \"lunar_nominal\"\n1 = \"dry_sand\"\n2 = \"mud.toml\"\n7 = \"lete_sand\"\n\
         [[terrain.soil_patches]]\nshape = \"circle\"\ncenter = [4.0, 0.0]\nradius = 1.5\nsoil = {SOFT_TABLE}\nedge = 0.2\n\
         [[terrain.soil_patches]]\nshape = \"rectangle\"\nx = [10.0, 12.0]\ny = [-1.0, 1.0]\nsoil = \"dry_sand\"\n\
         [[terrain.soil_patches]]\nshape = \"polygon\"\npoints = [[20.0, 0.0], [22.0, 0.0], [21.0, 2.0]]\nsoil = {{ n = 1.1, k_c = 990.0, k_phi = 1528430.0, cohesion = 1040.0, friction_angle_deg = 28.0, shear_modulus = 0.02 }}\nedge = 0\n"
    );
    let s = parse(&text).unwrap();
    assert!(s.soft());
    let l = layout(&s.terrain, &base).unwrap().unwrap();
    let labels: Vec<&str> = l.soils.iter().map(|(n, _)| n.as_str()).collect();
    // Class 0 and the first patch are the background's numbers; the
    // rectangle is class 1's; class 7 never appears.
    assert_eq!(labels, ["lunar_nominal", "dry_sand", "mud.toml", "patch 2"]);
    assert_eq!(l.soils[0].1, builtin("lunar_nominal"));
    assert_eq!(l.soils[1].1, builtin("dry_sand"));
    assert_eq!(l.soils[2].1.n, 0.8);
    assert_eq!(l.map.classes(), vec![0, 1, 2, 3]);
    // The raster's nodes, its fade into the background, the patches.
    assert_eq!(l.map.weights(0.0, 0.0), SoilWeights::single(1));
    assert_eq!(l.map.weights(1.0, 1.0), SoilWeights::single(2));
    assert_eq!(l.map.weights(-1.0, 1.0), SoilWeights::single(0));
    assert_eq!(l.map.weights(30.0, 0.0), SoilWeights::single(0));
    assert_eq!(l.map.weights(4.0, 0.5), SoilWeights::single(0));
    assert_eq!(l.map.weights(11.0, 0.0), SoilWeights::single(1));
    assert_eq!(l.map.weights(21.0, 1.0), SoilWeights::single(3));
    let w = l.map.weights(0.5, 0.0);
    assert_eq!(w.count, 2);
    assert!((w.weights[0] - 0.5).abs() < 1e-12, "{w:?}");
    // The ground reads as it was written.
    let back: GroundConfig = toml::from_str(&toml::to_string(&s.terrain).unwrap()).unwrap();
    assert_eq!(back, s.terrain);
    // The single-soil reading gives the background.
    assert_eq!(
        s.terrain.soil(&base).unwrap(),
        Some(builtin("lunar_nominal"))
    );
}

#[test]
fn a_single_soil_is_one_soil_everywhere_and_rigid_ground_has_none() {
    let base = dir("single");
    for (text, label) in [
        ("[terrain]\nsoil = \"dry_sand\"\n", "dry_sand"),
        (
            "[terrain.soil]\nn = 1.1\nk_c = 990.0\nk_phi = 1528430.0\ncohesion = 1040.0\nfriction_angle_deg = 28.0\nshear_modulus = 0.01\n",
            "background",
        ),
    ] {
        let s = parse(text).unwrap();
        let l = layout(&s.terrain, &base).unwrap().unwrap();
        assert_eq!(l.soils.len(), 1);
        assert_eq!(l.soils[0].0, label);
        assert_eq!(l.soils[0].1, builtin("dry_sand"));
        assert_eq!(l.map.is_uniform(), Some(0));
        assert_eq!(s.terrain.soil(&base).unwrap(), Some(l.soils[0].1));
        let back: GroundConfig = toml::from_str(&toml::to_string(&s.terrain).unwrap()).unwrap();
        assert_eq!(back, s.terrain);
    }
    let rigid = parse("[terrain]\nkind = \"flat\"\n").unwrap();
    assert!(layout(&rigid.terrain, &base).unwrap().is_none());
    assert!(!rigid.soft());
}

#[test]
fn a_map_without_a_background_must_cover_the_terrain() {
    let base = dir("cover");
    std::fs::write(base.join("classes.csv"), CLASSES_CSV).unwrap();
    let map = "[terrain.soil_map]\npath = \"classes.csv\"\n[terrain.soil_map.classes]\n0 = \"lunar_nominal\"\n1 = \"dry_sand\"\n2 = \"lete_sand\"\n";
    // The pixels span [−1.5, 1.5]²: a random terrain inside them is covered …
    let inside =
        format!("[terrain]\nkind = \"random\"\nz_r = 0.1\nextent = [-1.4, 1.4, -1.4, 1.4]\n{map}");
    let l = layout_of(&inside, &base).unwrap().unwrap();
    assert_eq!(l.soils.len(), 3);
    assert_eq!(l.map.background(), None);
    // … one beyond them is not …
    let beyond =
        format!("[terrain]\nkind = \"random\"\nz_r = 0.1\nextent = [-1.4, 2.0, -1.4, 1.4]\n{map}");
    let e = layout_of(&beyond, &base).unwrap_err();
    assert!(
        e.starts_with("terrain.soil_map: the soil map covers X [-1.5, 1.5], Y [-1.5, 1.5] m")
            && e.contains("X [-1.4, 2")
            && e.contains("background `soil`"),
        "{e}"
    );
    // … nor is an unbounded one.
    let e = layout_of(&format!("[terrain]\nkind = \"flat\"\n{map}"), &base).unwrap_err();
    assert!(
        e.starts_with("terrain.soil: the terrain is unbounded")
            && e.contains("a background soil is needed"),
        "{e}"
    );
    // The single-soil reading of such a ground says where to look.
    let s = parse(&format!("[terrain]\nkind = \"flat\"\n{map}")).unwrap();
    assert!(s.soft());
    let e = s.terrain.soil(&base).unwrap_err().to_string();
    assert!(
        e.contains("soil_layout") && e.contains("give [terrain] a background `soil`"),
        "{e}"
    );
}

#[test]
fn a_class_of_the_raster_without_a_soil_is_named_with_its_first_place() {
    let base = dir("missing");
    std::fs::write(base.join("classes.csv"), CLASSES_CSV).unwrap();
    let text = "[terrain]\nsoil = \"lunar_nominal\"\n[terrain.soil_map]\npath = \"classes.csv\"\n[terrain.soil_map.classes]\n0 = \"lunar_nominal\"\n1 = \"dry_sand\"\n";
    let e = layout_of(text, &base).unwrap_err();
    let place = format!("{}:6: row 3, column 3", base.join("classes.csv").display());
    assert!(
        e.starts_with(&format!(
            "terrain.soil_map.classes: class 2 of the soil map has no soil; it first appears at {place}"
        )) && e.contains("add `2 = "),
        "{e}"
    );
}

#[test]
fn a_soil_map_file_that_is_not_classes_is_refused_naming_the_file() {
    let base = dir("file");
    std::fs::write(base.join("half.csv"), "0,1\n1,0.5\n").unwrap();
    let head = "[terrain]\nsoil = \"lunar_nominal\"\n[terrain.soil_map]\n";
    let classes = "[terrain.soil_map.classes]\n0 = \"dry_sand\"\n";
    let e = layout_of(
        &format!("{head}path = \"half.csv\"\norigin = [0.0, 0.0]\nspacing = [1.0, 1.0]\n{classes}"),
        &base,
    )
    .unwrap_err();
    assert!(
        e.starts_with(&format!(
            "{}:2: row 2, column 2: the class 0.5 is not a whole number",
            base.join("half.csv").display()
        )),
        "{e}"
    );
    let e = layout_of(
        &format!("{head}path = \"half.csv\"\norigin = [0.0, 0.0]\n{classes}"),
        &base,
    )
    .unwrap_err();
    assert!(
        e.starts_with("terrain.soil_map.spacing: origin is given alone"),
        "{e}"
    );
    std::fs::write(base.join("map.png"), b"").unwrap();
    let e = layout_of(&format!("{head}path = \"map.png\"\n{classes}"), &base).unwrap_err();
    assert!(
        e.starts_with("terrain.soil_map.origin: a PNG soil map needs origin"),
        "{e}"
    );
    let e = parse(&format!("{head}path = \"half.csv\"\n")).unwrap_err();
    assert!(e.contains("terrain.soil_map has no classes"), "{e}");
    let e = parse(&format!(
        "{head}path = \"half.csv\"\n[terrain.soil_map.classes]\nsand = \"dry_sand\"\n"
    ))
    .unwrap_err();
    assert!(
        e.contains("terrain.soil_map.classes.sand: `sand` is not a soil class"),
        "{e}"
    );
    let e = parse(&format!(
        "{head}path = \"half.csv\"\nscale = 2.0\n{classes}"
    ))
    .unwrap_err();
    assert!(e.contains("terrain.soil_map: unknown field `scale`"), "{e}");
}

#[test]
fn bad_patches_are_refused_when_the_scenario_is_read_naming_the_key() {
    let patch = |body: &str| {
        parse(&format!(
            "[terrain]\nsoil = \"lunar_nominal\"\n[[terrain.soil_patches]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 1.0\nsoil = \"dry_sand\"\n[[terrain.soil_patches]]\n{body}"
        ))
        .unwrap_err()
    };
    for (body, want) in [
        (
            "shape = \"circle\"\ncenter = [0.0, 0.0]\nradius = -2.0\nsoil = \"dry_sand\"\n",
            "terrain.soil_patches[1].radius: must be > 0 m, got -2",
        ),
        (
            "shape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 0\nsoil = \"dry_sand\"\n",
            "terrain.soil_patches[1].radius: must be > 0 m, got 0",
        ),
        (
            "shape = \"rectangle\"\nx = [2.0, 1.0]\ny = [0.0, 1.0]\nsoil = \"dry_sand\"\n",
            "terrain.soil_patches[1].x: [2, 1] is inverted",
        ),
        (
            "shape = \"rectangle\"\nx = [1.0, 2.0]\ny = [1.0, 1.0]\nsoil = \"dry_sand\"\n",
            "terrain.soil_patches[1].y: [1, 1] is empty",
        ),
        (
            "shape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 1.0\nsoil = \"dry_sand\"\nedge = -0.5\n",
            "terrain.soil_patches[1].edge: must be ≥ 0 m, got -0.5",
        ),
        (
            "shape = \"hexagon\"\nsoil = \"dry_sand\"\n",
            "terrain.soil_patches[1]: unknown variant `hexagon`, expected one of `circle`, `rectangle`, `polygon`",
        ),
        (
            "shape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 1.0\nradious = 2.0\nsoil = \"dry_sand\"\n",
            "terrain.soil_patches[1]: unknown field `radious`",
        ),
        (
            "shape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 1.0\n",
            "terrain.soil_patches[1] has no soil",
        ),
        (
            "shape = \"polygon\"\npoints = [[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]\nsoil = \"dry_sand\"\n",
            "terrain.soil_patches[1].points: the edge from points[0] to points[1] meets",
        ),
        (
            "shape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 1.0\nsoil = 4\n",
            "terrain.soil_patches[1].soil = 4: give a built-in soil's name",
        ),
    ] {
        let e = patch(body);
        assert!(e.contains(want), "{body}: {e}");
    }
}

#[test]
fn bad_soils_of_classes_and_patches_are_refused_naming_where_they_are() {
    let base = dir("bad_soils");
    std::fs::write(base.join("classes.csv"), CLASSES_CSV).unwrap();
    let patch = |soil: &str| {
        format!(
            "[terrain]\nsoil = \"lunar_nominal\"\n[[terrain.soil_patches]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 1.0\nsoil = \"dry_sand\"\n[[terrain.soil_patches]]\nshape = \"rectangle\"\nx = [0.0, 1.0]\ny = [0.0, 1.0]\nsoil = {soil}\n"
        )
    };
    let e = layout_of(&patch(&SOFT_TABLE.replace("n = 1.0", "n = -1.0")), &base).unwrap_err();
    assert!(
        e.starts_with("terrain.soil_patches[1].soil: soil.n = -1:"),
        "{e}"
    );
    let e = layout_of(&patch("\"quicksand\""), &base).unwrap_err();
    assert!(
        e.starts_with(
            "terrain.soil_patches[1].soil = \"quicksand\": no built-in soil of that name"
        ) && e.contains("dry_sand"),
        "{e}"
    );
    let e = parse(&patch("{ n = 1.0, k_cc = 2.0 }")).unwrap_err();
    assert!(
        e.contains("terrain.soil_patches[1].soil: unknown field `k_cc`"),
        "{e}"
    );
    // A class's soil, and a listed class the raster lacks, are checked too.
    let map = |soil: &str| {
        format!(
            "[terrain]\nsoil = \"lunar_nominal\"\n[terrain.soil_map]\npath = \"classes.csv\"\n[terrain.soil_map.classes]\n0 = \"lunar_nominal\"\n1 = \"dry_sand\"\n2 = \"lete_sand\"\n9 = {soil}\n"
        )
    };
    assert_eq!(
        layout_of(&map("\"dry_sand\""), &base)
            .unwrap()
            .unwrap()
            .soils
            .len(),
        3
    );
    let e = layout_of(&map("\"quicksand\""), &base).unwrap_err();
    assert!(
        e.starts_with("terrain.soil_map.classes.9 = \"quicksand\": no built-in soil"),
        "{e}"
    );
    let e = layout_of(
        &map(&SOFT_TABLE.replace("shear_modulus = 0.018", "shear_modulus = 0.0")),
        &base,
    )
    .unwrap_err();
    assert!(
        e.starts_with("terrain.soil_map.classes.9: soil.shear_modulus = 0:"),
        "{e}"
    );
    // A background soil's message is the one a single soil has always had.
    let e = layout_of("[terrain]\nsoil = \"quicksand\"\n", &base).unwrap_err();
    assert!(
        e.starts_with("terrain.soil = \"quicksand\": no built-in soil"),
        "{e}"
    );
}

#[test]
fn patches_over_no_soil_are_refused() {
    let base = dir("no_soil");
    let text = "[terrain]\nkind = \"flat\"\n[[terrain.soil_patches]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 1.0\nsoil = \"dry_sand\"\n";
    let s = parse(text).unwrap();
    assert!(s.soft());
    let e = layout(&s.terrain, &base).unwrap_err();
    assert!(
        e.starts_with("terrain.soil_patches: the soil patches lie over no soil")
            && e.contains("soil = \"lunar_nominal\""),
        "{e}"
    );
    assert!(s.terrain.soil(&base).is_err());
    let e = parse("[terrain]\nsoil_patches = 3\n").unwrap_err();
    assert!(
        e.contains("terrain.soil_patches = 3: give each patch as a [[terrain.soil_patches]] table"),
        "{e}"
    );
}

#[test]
fn a_shape_error_beside_soil_patches_is_still_located_at_its_key() {
    let e = parse("[terrain]\nkind = \"slope\"\nangel_deg = 1.0\nsoil = \"dry_sand\"\n[[terrain.soil_patches]]\nshape = \"circle\"\ncenter = [0.0, 0.0]\nradius = 1.0\nsoil = \"dry_sand\"\n")
        .unwrap_err();
    assert!(e.contains("line 4") && e.contains("angel_deg"), "{e}");
}
