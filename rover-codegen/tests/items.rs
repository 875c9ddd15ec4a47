//! A generated plant offers the items of `rover_codegen::Item::ALL`, no
//! more and no fewer: in a standalone module, in the derive's plant, and in
//! the derive's stand-in for an invalid description (which code using the
//! rover must still type-check against). The cases of rover-derive's
//! `compile_fail` test then use each listed item on both plants.

use std::collections::BTreeSet;
use std::path::Path;

use rover_codegen::items::Item;

/// The listed items' names, with or without the Jacobian's.
fn listed(jacobian: bool) -> BTreeSet<String> {
    Item::ALL
        .iter()
        .filter(|item| jacobian || !item.needs_jacobian())
        .map(|item| item.name().to_string())
        .collect()
}

/// The impls of type `ty` in `file`.
fn impls<'a>(file: &'a syn::File, ty: &'a str) -> impl Iterator<Item = &'a syn::ItemImpl> {
    file.items.iter().filter_map(move |item| match item {
        syn::Item::Impl(i) => match &*i.self_ty {
            syn::Type::Path(p) if p.path.is_ident(ty) => Some(i),
            _ => None,
        },
        _ => None,
    })
}

/// What `ty` offers in `file`: the constants and functions of its inherent
/// impls that are visible outside (`pub`, `pub(crate)`), and the last path
/// segment of each trait it implements.
fn surface(file: &syn::File, ty: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for i in impls(file, ty) {
        if let Some((path, _)) = &i.trait_ {
            out.insert(path.segments.last().unwrap().ident.to_string());
            continue;
        }
        for member in &i.items {
            match member {
                syn::ImplItem::Const(c) if !matches!(c.vis, syn::Visibility::Inherited) => {
                    out.insert(c.ident.to_string());
                }
                syn::ImplItem::Fn(f) if !matches!(f.vis, syn::Visibility::Inherited) => {
                    out.insert(f.sig.ident.to_string());
                }
                _ => {}
            }
        }
    }
    out
}

/// The functions of the trait impls of `ty` in `file`.
fn trait_methods(file: &syn::File, ty: &str) -> BTreeSet<String> {
    impls(file, ty)
        .filter(|i| i.trait_.is_some())
        .flat_map(|i| &i.items)
        .filter_map(|member| match member {
            syn::ImplItem::Fn(f) => Some(f.sig.ident.to_string()),
            _ => None,
        })
        .collect()
}

fn builtin(name: &str) -> rover_spec::Spec {
    let source = rover_models::builtin_path(name).unwrap();
    rover_spec::load_str(rover_models::builtin(name).unwrap(), source).unwrap()
}

/// The derive's expansion of `#[rover(…)] struct <name>;`, parsed.
fn derive(attribute: &str, name: &str) -> syn::File {
    let input: syn::DeriveInput =
        syn::parse_str(&format!("#[rover({attribute})] pub struct {name};")).unwrap();
    let base = Path::new(env!("CARGO_MANIFEST_DIR"));
    syn::parse2(rover_codegen::expand_derive_in(&input, base)).unwrap()
}

#[test]
fn generated_modules_offer_exactly_the_listed_items() {
    // swing4's right-hand side runs in four lanes, exomars' does not.
    for rover in ["swing4", "exomars"] {
        for jacobian in [true, false] {
            let options = rover_codegen::ModuleOptions {
                type_name: Some("Plant".into()),
                jacobian,
                level: None,
            };
            let module =
                rover_codegen::generate_module_with(&builtin(rover), rover, &options).unwrap();
            let file = syn::parse_file(&module).unwrap();
            assert_eq!(
                surface(&file, "Plant"),
                listed(jacobian),
                "{rover}, Jacobian {jacobian}"
            );
        }
    }
}

#[test]
fn the_derives_plant_offers_the_listed_items_and_its_description() {
    let file = derive(r#"file = "tests/data/toy.toml", jacobian = true"#, "Toy");
    let mut expected = listed(true);
    // The derive's own trait: the description the plant came from.
    expected.insert("Described".into());
    assert_eq!(surface(&file, "ToyPlant"), expected);
}

#[test]
fn the_stand_in_of_an_invalid_description_offers_every_listed_item() {
    let file = derive(r#"name = "bad", gravity = -1.0"#, "Bad");
    let offered = surface(&file, "BadPlant");
    let mut expected = listed(true);
    expected.insert("Described".into());
    let missing: Vec<_> = expected.difference(&offered).collect();
    assert!(missing.is_empty(), "the stand-in lacks {missing:?}");
    // Beyond the list, only inherent copies of its traits' methods (so
    // that a call takes its sizes from its arguments).
    let copies = trait_methods(&file, "BadPlant");
    let extra: Vec<_> = offered
        .difference(&expected)
        .filter(|name| !copies.contains(*name))
        .collect();
    assert!(extra.is_empty(), "the stand-in offers unlisted {extra:?}");
}
