//! The plots must build on a fresh machine: no crate that loads system fonts
//! through fontconfig or freetype may enter the build. plotters' default
//! `ttf` feature would bring `font-kit` (and with it fontconfig/freetype
//! bindings) into the workspace lock file, so the lock file is checked; it is
//! what `cargo tree -p rover-plot | grep -i -E "font-kit|fontconfig|freetype"`
//! would show, without running cargo.

#[test]
fn the_lock_file_has_no_system_font_crates() {
    let lock = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../Cargo.lock"))
        .expect("the workspace Cargo.lock is committed next to the root Cargo.toml");
    assert!(lock.contains("name = \"plotters\""), "plotters is locked");
    assert!(
        lock.contains("name = \"dejavu\""),
        "the embedded font is locked"
    );
    for line in lock.lines().filter(|l| l.starts_with("name = ")) {
        let name = line
            .trim_start_matches("name = ")
            .trim_matches('"')
            .to_lowercase();
        for banned in ["font-kit", "fontconfig", "freetype"] {
            assert!(
                !name.contains(banned),
                "`{name}` is in Cargo.lock: it needs system font libraries"
            );
        }
    }
}

#[test]
fn plotters_is_declared_without_its_ttf_feature() {
    let manifest =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../Cargo.toml")).unwrap();
    let line = manifest
        .lines()
        .find(|l| l.trim_start().starts_with("plotters ="))
        .expect("plotters is a workspace dependency");
    assert!(line.contains("default-features = false"), "{line}");
    assert!(!line.contains("\"ttf\""), "{line}");
    assert!(line.contains("\"ab_glyph\""), "{line}");
}
