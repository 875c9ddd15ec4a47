//! The scenario's `[terrain]` table: parsing, checks, building.

use std::path::Path;

use rover_dynamics::height_field::*;
use rover_terrain::*;

use super::support::*;

// ---------------------------------------------------------------- scenario config

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct Scenario {
    #[serde(default)]
    terrain: TerrainConfig,
}

fn config(toml_text: &str) -> Result<TerrainConfig, toml::de::Error> {
    toml::from_str::<Scenario>(toml_text).map(|s| s.terrain)
}

fn build(toml_text: &str, base_dir: &Path) -> Result<Terrain, TerrainError> {
    config(toml_text).expect("valid TOML").build(base_dir)
}

#[test]
fn config_builds_every_kind() {
    let here = Path::new(".");
    assert_eq!(config("").unwrap(), TerrainConfig::default());
    let t = build("[terrain]\nkind = \"flat\"\nheight = -1.5\n", here).unwrap();
    assert_eq!(h(&t, 3.0, 4.0), -1.5);
    let t = build(
        "[terrain]\nkind = \"slope\"\nangle_deg = 45\ndirection_deg = 180\n",
        here,
    )
    .unwrap();
    assert_close(h(&t, -2.0, 7.0), 2.0, 1e-15, "45° slope rising towards -X");
    let t = build(
        "[terrain]\nkind = \"bump\"\nheight = 0.1\nwidth = 0.4\ncenter = [2.0, 0.0]\n\
         footprint = \"round\"\n",
        here,
    )
    .unwrap();
    assert_close(h(&t, 2.0, 0.1), 0.05, 1e-15, "round bump mid-flank");
    let t = build(
        "[terrain]\nkind = \"ditch\"\ndepth = 0.2\nwidth = 1.0\nbottom_width = 0.5\n\
         center = [0.0, 3.0]\ndirection_deg = 90\n",
        here,
    )
    .unwrap();
    assert_eq!(h(&t, 9.0, 3.2), -0.2);
    let t = build(
        "[terrain]\nkind = \"step\"\nheight = 0.1\nposition = [1.0, 0.0]\n",
        here,
    )
    .unwrap();
    assert_close(h(&t, 1.0, 0.0), 0.05, 1e-15, "default 1 cm ramp, middle");
    assert_eq!(h(&t, 1.005, 0.0), 0.1);
    let t = build(
        "[terrain]\nkind = \"sinusoid\"\namplitude = 0.02\nwavelength = 2.0\n",
        here,
    )
    .unwrap();
    assert_close(h(&t, 0.5, 0.0), 0.02, 1e-17, "sinusoid crest");
    let t = build(
        "[terrain]\nkind = \"random\"\nz_r = 0.2\nseed = 3\nextent = [-1.0, 2.0, -1.0, 1.0]\n\
         interpolation = \"bilinear\"\nedge = \"clamp\"\n",
        here,
    )
    .unwrap();
    let Terrain::Grid(grid) = &t else {
        panic!("random terrain is a grid: {t:?}")
    };
    let expected = RandomField {
        seed: 3,
        extent: Bounds {
            x_min: -1.0,
            x_max: 2.0,
            y_min: -1.0,
            y_max: 1.0,
        },
        interpolation: Interpolation::Bilinear,
        edge: EdgePolicy::Clamp,
        ..RandomField::default()
    };
    assert_eq!(grid, &expected.grid().unwrap());
    assert!(t.height(50.0, 0.0).is_ok());
}

#[test]
fn config_loads_files_relative_to_the_scenario() {
    let dir = scratch("scenario");
    std::fs::create_dir_all(dir.join("maps")).unwrap();
    let grid = bumpy_grid(4, 4);
    write_asc(&grid, &dir.join("maps/site.ASC")).unwrap();
    write_geotiff(&grid, &dir.join("maps/site.tiff")).unwrap();
    std::fs::write(dir.join("maps/site.txt"), "1,2\n3,4\n").unwrap();
    let t = build(
        "[terrain]\nkind = \"file\"\npath = \"maps/site.ASC\"\nedge = \"clamp\"\n",
        &dir,
    )
    .unwrap();
    assert_eq!(
        t,
        Terrain::Grid(grid.clone().with_edge_policy(EdgePolicy::Clamp))
    );
    let t = build(
        "[terrain]\nkind = \"file\"\npath = \"maps/site.tiff\"\n",
        &dir,
    )
    .unwrap();
    assert_eq!(t, Terrain::Grid(grid.clone()));
    // scale and offset apply to every format.
    let t = build(
        "[terrain]\nkind = \"file\"\npath = \"maps/site.txt\"\nformat = \"csv\"\n\
         origin = [0.0, 0.0]\nspacing = [1.0, 1.0]\nscale = 0.5\noffset = 10\n",
        &dir,
    )
    .unwrap();
    assert_eq!(h(&t, 1.0, 1.0), 12.0);
}

#[test]
fn config_errors_name_the_parameter() {
    let dir = scratch("scenario_errors");
    std::fs::create_dir_all(&dir).unwrap();
    write_asc(&bumpy_grid(3, 3), &dir.join("a.asc")).unwrap();
    write_png(
        &Grid::new([0.0, 0.0], [1.0, 1.0], 2, 2, vec![0.0; 4]).unwrap(),
        &dir.join("a.png"),
        SampleScale {
            scale: 1.0,
            offset: 0.0,
        },
    )
    .unwrap();
    let cases = [
        (
            "kind = \"file\"\npath = \"a.png\"\norigin = [0.0, 0.0]\nspacing = [1.0, 1.0]\n",
            "terrain.scale: a PNG height map needs scale (metres per count)\n  = help: set scale \
             (and offset, the height of sample 0), e.g. scale = 0.001",
        ),
        (
            "kind = \"file\"\npath = \"a.png\"\nscale = 0.01\n",
            "terrain.origin: a PNG height map needs origin and spacing\n  = help: set origin = \
             [x, y] (centre of the bottom-left pixel) and spacing = [dx, dy] in metres",
        ),
        (
            "kind = \"file\"\npath = \"a.png\"\nscale = 0.01\norigin = [0.0, 0.0]\n",
            "terrain.spacing: origin is given without spacing\n  = help: give both origin = [x, \
             y] and spacing = [dx, dy], or neither",
        ),
        (
            "kind = \"file\"\npath = \"a.png\"\nscale = 0.01\norigin = [0.0, 0.0]\nspacing = [0.0, 1.0]\n",
            "terrain.spacing[0]: must be > 0 m, got 0\n  = help: give a positive value in m",
        ),
        (
            "kind = \"file\"\npath = \"a.asc\"\norigin = [0.0, 0.0]\nspacing = [1.0, 1.0]\n",
            "terrain.origin: ESRI ASCII grid files carry their own origin and spacing\n  = help: \
             remove origin and spacing from [terrain]",
        ),
        (
            "kind = \"file\"\npath = \"a.dem\"\n",
            &format!(
                "terrain.format: cannot tell the format of `{}` from its extension\n  = help: set \
                 format = \"asc\", \"csv\", \"png\" or \"geotiff\"",
                dir.join("a.dem").display()
            ),
        ),
        (
            "kind = \"bump\"\nheight = 0.1\nwidth = 0.0\ncenter = [0.0, 0.0]\n",
            "terrain.width: must be > 0 m, got 0\n  = help: give a positive value in m",
        ),
        (
            "kind = \"random\"\nz_r = 0.2\npatch_radius = -1\n",
            "terrain.patch_radius: must be ≥ 0 m, got -1\n  = help: give a non-negative value in m",
        ),
    ];
    for (body, expected) in cases {
        let result = build(&format!("[terrain]\n{body}"), &dir);
        assert_eq!(message(result), expected, "case:\n{body}");
    }
}

#[test]
fn config_rejects_unknown_keys_and_kinds() {
    for (body, needle) in [
        (
            "kind = \"random\"\nz_r = 0.2\nsede = 4\n",
            "unknown field `sede`",
        ),
        (
            "kind = \"bump\"\nheight = 0.1\nwidth = 1\ncenter = [0, 0]\nradius = 2\n",
            "unknown field `radius`",
        ),
        ("kind = \"flat\"\nheigth = 1\n", "unknown field `heigth`"),
        ("kind = \"hills\"\n", "unknown variant `hills`"),
        ("kind = \"random\"\n", "missing field `z_r`"),
        (
            "kind = \"file\"\npath = \"a.asc\"\nformat = \"tif\"\n",
            "unknown variant `tif`",
        ),
        (
            "kind = \"random\"\nz_r = 0.1\nedge = \"wrap\"\n",
            "unknown variant `wrap`",
        ),
    ] {
        let error = config(&format!("[terrain]\n{body}"))
            .unwrap_err()
            .to_string();
        assert!(error.contains(needle), "case:\n{body}\ngot: {error}");
    }
}

#[test]
fn config_serializes_back_to_the_same_table() {
    for body in [
        "kind = \"flat\"\n",
        "kind = \"random\"\nz_r = 0.5\nseed = 9\nnode_spacing = 0.25\n",
        "kind = \"file\"\npath = \"x.png\"\nscale = 0.001\norigin = [1.0, 2.0]\nspacing = [0.1, 0.1]\n",
        "kind = \"step\"\nheight = 0.1\nposition = [1.0, 0.0]\nramp_width = 0.0\n",
    ] {
        let c = config(&format!("[terrain]\n{body}")).unwrap();
        let text = toml::to_string(&c).unwrap();
        let back: TerrainConfig = toml::from_str(&text).unwrap();
        assert_eq!(back, c, "{text}");
    }
}
