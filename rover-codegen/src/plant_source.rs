//! The Rust source of a generated plant type: the struct, its constants,
//! the fast fixed-size methods and the `rover_dynamics::Plant` impl.
//!
//! Each item of [`Item::ALL`] is written by its own function, as tokens
//! (`quote!`). The straight-line bodies are text, printed by
//! [`crate::emit`] and [`crate::lanes`] (whose tests read it), with block
//! headings as `__rover_comment!("…");` markers that the standalone module
//! turns into `//` comments and the derive drops; they are lexed into
//! tokens here, as are the literals, so that each reads exactly as printed
//! (a float as [`literal`] writes it, a name as Rust's `Debug` quotes it).

use std::fmt::Write;

use proc_macro2::{Ident, LexError, Literal, TokenStream};
use quote::{format_ident, quote};
use rover_spec::Spec;

use crate::emit::{Block, OpCount, emit, literal};
use crate::items::{Item, Kind};
use crate::lanes;
use crate::simplify::simplify;
use crate::trace::{Function, Traced, trace_spec_at};

mod members;
mod traits;

/// The path of libm in generated code.
const LIBM: &str = "::libm";

/// What to generate.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// Name of the plant type.
    pub type_name: String,
    /// Whether to emit the exact Jacobian `∂(ẋ, ẇ)/∂(x, w)` as `jacobian_fixed`.
    pub jacobian: bool,
    /// Whether block headings are kept (as comment markers).
    pub comments: bool,
    /// Visibility of the generated items (`pub`, `pub(crate)`, empty).
    pub visibility: String,
    /// A reduced fidelity level, or `None` for the full model.
    pub level: Option<crate::trace::Level>,
}

/// The generated source and its operation counts.
#[derive(Clone, Debug)]
pub struct PlantSource {
    /// The items, as tokens (unformatted).
    pub code: TokenStream,
    /// Counts per function: derivatives, mass matrix, wheels, Jacobian.
    pub ops: Vec<(&'static str, OpCount)>,
    /// How much of the right-hand side runs in four lanes, if any.
    pub lanes: Option<String>,
}

/// The plant type for `spec`. An error is text of the generator's own
/// that does not lex: a bug of the generator.
pub fn plant_source(spec: &Spec, options: &Options) -> Result<PlantSource, LexError> {
    let traced = trace_spec_at(spec, options.jacobian, options.level.as_ref());
    let (plant, ops, lanes) = Plant::new(spec, options, &traced)?;
    Ok(PlantSource {
        code: plant.items(),
        ops,
        lanes,
    })
}

/// What the items' functions read: the rover's sizes and names, and the
/// traced functions' bodies, all as tokens.
struct Plant {
    /// The plant type's name.
    name: TokenStream,
    /// The struct's visibility.
    vis: TokenStream,
    /// The number of degrees of freedom N, of suspension coordinates m, of
    /// wheels; 2N, the Jacobian's size.
    n: Literal,
    m: Literal,
    k: Literal,
    two_n: Literal,
    /// The rover's name for one-line documentation, and as a literal (one
    /// line too).
    rover_doc: String,
    rover: TokenStream,
    /// The coordinates and wheels for the struct's documentation.
    coordinates_doc: String,
    wheels_doc: String,
    /// The names of the coordinates and wheels as literals.
    coordinate_names: Vec<TokenStream>,
    wheel_names: Vec<TokenStream>,
    /// The description's spring neutrals, each wheel's tyre and radius.
    neutrals: Vec<TokenStream>,
    tyres: Vec<TokenStream>,
    radii: Vec<TokenStream>,
    /// The steering parameter of `wheels_array`: `_steer` when no wheel steers.
    steer: Ident,
    /// The generated functions' bodies.
    bodies: Bodies,
}

impl Plant {
    /// Everything the items need from `spec` and its traced functions,
    /// the operation counts and the note on the lanes.
    fn new(
        spec: &Spec,
        options: &Options,
        traced: &Traced,
    ) -> Result<(Plant, Ops, Option<String>), LexError> {
        let model = &spec.model;
        let (n, m, k) = (model.dof(), model.m(), model.wheels.len());
        let (bodies, ops, lanes) = Bodies::new(traced, options.comments)?;
        let coordinates_doc: Vec<String> = spec
            .coordinate_names
            .iter()
            .enumerate()
            .map(|(i, c)| format!("y{} `{c}`", i + 1))
            .collect();
        let steers = model.wheels.iter().any(|w| w.steerable);
        let plant = Plant {
            name: options.type_name.parse()?,
            vis: options.visibility.parse()?,
            n: Literal::usize_unsuffixed(n),
            m: Literal::usize_unsuffixed(m),
            k: Literal::usize_unsuffixed(k),
            two_n: Literal::usize_unsuffixed(2 * n),
            rover_doc: one_line(&spec.name),
            rover: string(&one_line(&spec.name))?,
            coordinates_doc: one_line(&coordinates_doc.join(", ")),
            wheels_doc: one_line(&spec.wheel_names.join(", ")),
            coordinate_names: strings(&spec.coordinate_names)?,
            wheel_names: strings(&spec.wheel_names)?,
            neutrals: floats(model.coordinates.iter().map(|c| c.neutral))?,
            tyres: model
                .wheels
                .iter()
                .map(|w| tyre(&w.tyre()))
                .collect::<Result<_, _>>()?,
            radii: floats(model.wheels.iter().map(|w| w.radius))?,
            steer: format_ident!("{}", if steers { "steer" } else { "_steer" }),
            bodies,
        };
        Ok((plant, ops, lanes))
    }

    /// The struct, then [`Item::ALL`] block by block: each trait impl, and
    /// each run of constants and methods as one inherent `impl`.
    fn items(&self) -> TokenStream {
        let mut out = self.struct_item();
        for block in Item::blocks() {
            out.extend(match block {
                [item] if item.kind() == Kind::Impl => self.item(*item),
                members => self.inherent_impl(members),
            });
        }
        out
    }

    /// One item: a trait impl whole, a constant or a method with the
    /// private functions only it calls.
    fn item(&self, item: Item) -> TokenStream {
        match item {
            Item::Default => self.default_impl(),
            Item::Name => self.name_const(),
            Item::Dof => self.dof_const(),
            Item::Wheels => self.wheels_const(),
            Item::Coordinates => self.coordinates_const(),
            Item::WheelNames => self.wheel_names_const(),
            Item::SpringNeutrals => self.spring_neutrals_const(),
            Item::MinCosRoll => self.min_cos_roll_const(),
            Item::New => self.new_fn(),
            Item::CurrentNeutrals => self.spring_neutrals_fn(),
            Item::DerivativesArray => self.derivatives_array(),
            Item::DerivativesPortable => self.derivatives_portable(),
            Item::MassMatrixArray => self.mass_matrix_array(),
            Item::WheelsArray => self.wheels_array(),
            Item::JacobianArray => self.jacobian_array(),
            Item::JacobianFixed => self.jacobian_fixed(),
            Item::Tyres => self.tyres_const(),
            Item::Radii => self.radii_const(),
            Item::Ground => self.ground_fn(),
            Item::DerivativesOnGround => self.derivatives_on_ground(),
            Item::Plant => self.plant_impl(),
            Item::FixedPlant => self.fixed_plant_impl(),
        }
    }

    /// The struct: the spring neutrals are its state (active suspension
    /// moves them), the rest is constants.
    fn struct_item(&self) -> TokenStream {
        let Plant {
            name, vis, n, k, m, ..
        } = self;
        let title = format!(
            " The `{}` rover as a generated plant: {n} degrees of freedom",
            self.rover_doc
        );
        let sizes = format!(
            " (X, Y, Z, φ, θ, ψ, {}), {k} wheels ({}).",
            self.coordinates_doc, self.wheels_doc
        );
        quote! {
            #[doc = #title]
            #[doc = #sizes]
            ///
            /// Straight-line code traced from the equations of `rover-dynamics` with
            /// this rover's constants folded in; no heap, no panics, `no_std`.
            #[derive(Clone, Copy, Debug, PartialEq)]
            #vis struct #name {
                neutral: [f64; #m],
            }
        }
    }

    /// One inherent `impl` of `members`, in their order; the lints of
    /// machine-written code are off.
    fn inherent_impl(&self, members: &[Item]) -> TokenStream {
        let name = &self.name;
        let members = members.iter().map(|item| self.item(*item));
        quote! {
            #[allow(clippy::all, clippy::pedantic, unused_variables)]
            impl #name {
                #(#members)*
            }
        }
    }
}

/// The operation counts of the generated functions, for the header.
type Ops = Vec<(&'static str, OpCount)>;

/// The bodies of the generated functions.
struct Bodies {
    /// The right-hand side's copies.
    rhs: Rhs,
    /// The bodies of `mass_matrix_array`, `wheels_array` and, when asked
    /// for, `jacobian_array`.
    mass: TokenStream,
    wheels: TokenStream,
    jacobian: Option<TokenStream>,
}

impl Bodies {
    /// The traced functions emitted, with block headings if `comments`;
    /// their operation counts, in the header's order; the note on the lanes.
    fn new(traced: &Traced, comments: bool) -> Result<(Bodies, Ops, Option<String>), LexError> {
        let (rhs, rhs_ops, lanes) = Rhs::new(traced, comments)?;
        let (mass, mass_ops) = function_body(&traced.mass_matrix, comments)?;
        let (wheels, wheel_ops) = function_body(&traced.wheels, comments)?;
        let mut ops = vec![
            ("derivatives", rhs_ops),
            ("mass_matrix", mass_ops),
            ("wheels", wheel_ops),
        ];
        let jacobian = match &traced.jacobian {
            Some(f) => {
                let (body, jac_ops) = function_body(f, comments)?;
                ops.push(("jacobian", jac_ops));
                Some(body)
            }
            None => None,
        };
        let bodies = Bodies {
            rhs,
            mass,
            wheels,
            jacobian,
        };
        Ok((bodies, ops, lanes))
    }
}

/// The right-hand side's two copies, for x86-64-v4 and for the crate's own
/// target: a four-wheeled rover's per-wheel work in four-lane operations,
/// one statement list printed for each copy; otherwise one scalar body
/// (`derivatives_body`) that both copies inline.
struct Rhs {
    v4: TokenStream,
    portable: TokenStream,
    shared: Option<TokenStream>,
}

impl Rhs {
    /// The copies of the traced derivatives, their operation counts (of the
    /// scalar code, lanes or not) and the note on the lanes, if any.
    fn new(traced: &Traced, comments: bool) -> Result<(Rhs, OpCount, Option<String>), LexError> {
        // Simplified once: emitted as scalar code, or planned in four lanes.
        let derivatives = simplify(&traced.derivatives);
        let (blocks, ops) = emit(&derivatives, LIBM);
        let checks = rhs_checks(&traced.pivot_rows);
        // Each input's lane is recorded by the trace.
        let seeds = lanes::seeds(&derivatives, |k| derivatives.inputs[k].lane.clone());
        let Some(plan) = lanes::plan(&derivatives, &seeds) else {
            let call: TokenStream = quote!(self.derivatives_body(x, w, loads, xdot, wdot));
            let mut body = body(&blocks, comments).parse::<TokenStream>()?;
            body.extend(checks);
            let rhs = Rhs {
                v4: call.clone(),
                portable: call,
                shared: Some(body),
            };
            return Ok((rhs, ops, None));
        };
        let copy = |avx| -> Result<TokenStream, LexError> {
            let mut body: TokenStream = lanes::emit(&derivatives, &plan, avx, LIBM).parse()?;
            body.extend(checks.clone());
            Ok(body)
        };
        let note = format!(
            "{} four-lane operations ({} of {} scalar ones), {} sums over the lanes",
            plan.vector_ops(),
            plan.packed_ops,
            plan.total_ops,
            plan.lane_sums()
        );
        let rhs = Rhs {
            v4: copy(true)?,
            portable: copy(false)?,
            shared: None,
        };
        Ok((rhs, ops, Some(note)))
    }
}

/// After the outputs of the right-hand side: the checks the generic plant
/// makes too.
fn rhs_checks(pivot_rows: &[usize]) -> TokenStream {
    let pl = plant_path();
    let pivot = |r: &usize| format_ident!("pivot_{r}");
    let positive = pivot_rows.iter().map(pivot);
    let pivots = pivot_rows.iter().map(|r| {
        let (row, num, den) = (
            Literal::usize_unsuffixed(*r),
            pivot(r),
            format_ident!("pivot_den_{r}"),
        );
        quote!((#row, #num, #den))
    });
    // Each pivot is a ratio whose denominator the earlier checks made
    // positive: its numerator's sign decides. One test for all of them
    // (`&`, not `&&`: one branch; false for NaN), and the error, which
    // divides the failing value out to report it, built out of line.
    quote! {
        if f64::abs(cos_roll) < Self::MIN_COS_ROLL {
            return Err(#pl::PlantError::AttitudeSingular { roll: x[3] });
        }
        if #((#positive > 0.0))&* {
            return Ok(());
        }
        Self::singular_mass([#(#pivots),*])
    }
}

/// The statements of a traced function, simplified, and their counts.
fn function_body(f: &Function, comments: bool) -> Result<(TokenStream, OpCount), LexError> {
    let (blocks, ops) = emit(&simplify(f), LIBM);
    Ok((body(&blocks, comments).parse()?, ops))
}

/// Statements of blocks, with their headings as comment markers.
fn body(blocks: &[Block], comments: bool) -> String {
    let mut s = String::new();
    for b in blocks {
        if comments && let Some(t) = &b.title {
            let t = one_line(t).replace(['"', '\\'], "'");
            let _ = writeln!(s, "__rover_comment!(\"{t}\");");
        }
        for l in &b.lines {
            s.push_str(l);
            s.push('\n');
        }
    }
    s
}

/// Text from the description made safe for a one-line comment.
fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}

/// A string literal as Rust's `Debug` quotes it.
fn string(s: &str) -> Result<TokenStream, LexError> {
    format!("{s:?}").parse()
}

/// String literals of `items`.
fn strings(items: &[String]) -> Result<Vec<TokenStream>, LexError> {
    items.iter().map(|s| string(s)).collect()
}

/// A float literal that reads back to the same bits ([`literal`]; a
/// negative one is a negation).
fn float(v: f64) -> Result<TokenStream, LexError> {
    literal(v).parse()
}

/// Float literals of `values`.
fn floats(values: impl Iterator<Item = f64>) -> Result<Vec<TokenStream>, LexError> {
    values.map(float).collect()
}

/// A wheel's tyre as a `Tyre` literal.
fn tyre(t: &rover_dynamics::wheel_law::Tyre) -> Result<TokenStream, LexError> {
    let stiffness = float(t.stiffness)?;
    let damping = float(t.damping)?;
    let (mu_x, mu_y) = (float(t.mu_x)?, float(t.mu_y)?);
    let cornering = float(t.cornering_stiffness)?;
    let rolling = float(t.rolling_resistance)?;
    Ok(quote! {
        ::rover_dynamics::wheel_law::Tyre {
            stiffness: #stiffness,
            damping: #damping,
            mu_x: #mu_x,
            mu_y: #mu_y,
            cornering_stiffness: #cornering,
            rolling_resistance: #rolling
        }
    })
}

/// `rover_dynamics::plant` in generated code.
pub(crate) fn plant_path() -> TokenStream {
    quote!(::rover_dynamics::plant)
}

/// nalgebra as rover-dynamics re-exports it (one version for every user).
pub(crate) fn nalgebra_path() -> TokenStream {
    quote!(::rover_dynamics::nalgebra)
}

/// `rover_dynamics::wheel_ground` in generated code.
pub(crate) fn ground_path() -> TokenStream {
    quote!(::rover_dynamics::wheel_ground)
}

/// A plant type's name: a Rust identifier that is not a keyword (`Self`,
/// `type`, …) nor raw (`r#…`); otherwise what is wrong and how to fix it.
pub fn check_type_name(name: &str) -> Result<(), String> {
    // Word characters that do not parse as an identifier: a keyword (or `_`).
    let keyword = name.starts_with(|c: char| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && syn::parse_str::<syn::Ident>(name).is_err();
    if name.starts_with("r#") || syn::parse_str::<syn::Ident>(name).is_err() {
        let what = if keyword {
            "is a Rust keyword"
        } else {
            "is not a Rust identifier"
        };
        return Err(format!(
            "the type name {name:?} {what}: use letters, digits and underscores, starting with an uppercase letter, and not a keyword (e.g. MyRover)"
        ));
    }
    Ok(())
}
