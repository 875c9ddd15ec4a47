//! The Rust source of a generated plant type: the struct, its constants,
//! the fast fixed-size methods and the `rover_dynamics::Plant` impl.
//!
//! Written as text (then parsed, so a mistake here is a parse error, not
//! wrong code): straight-line bodies from [`crate::emit`], with block
//! headings as `__rover_comment!("…");` markers that the standalone module
//! turns into `//` comments and the derive drops.

use std::fmt::Write;

use rover_spec::Spec;

use crate::emit::{Block, OpCount, emit};
use crate::lanes;
use crate::simplify::simplify;
use crate::trace::{Function, Traced, trace_spec_at};

/// The path of `rover_dynamics::plant` in generated code.
const PLANT: &str = "::rover_dynamics::plant";
/// nalgebra as rover-dynamics re-exports it (one version for every user).
const NA: &str = "::rover_dynamics::nalgebra";
/// The features of the right-hand side's second copy, as the dispatch checks them.
const V4_FEATURES: &str = rover_dynamics::cpu::X86_64_V4_FEATURES;
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
    /// The items, unformatted Rust.
    pub code: String,
    /// Counts per function: derivatives, mass matrix, wheels, Jacobian.
    pub ops: Vec<(&'static str, OpCount)>,
    /// How much of the right-hand side runs in four lanes, if any.
    pub lanes: Option<String>,
}

/// The path of `rover_dynamics::wheel_ground` in generated code.
const GROUND: &str = "::rover_dynamics::wheel_ground";

/// The force path's constants and methods: each wheel's tyre and radius as
/// constants, and the whole right-hand side on a height field, which runs
/// the contact search and the wheel law of `rover_dynamics::wheel_ground`
/// (the generic plant's very code) with those constants, then the traced
/// equations.
fn ground_methods(spec: &Spec, n: usize, k: usize) -> String {
    use crate::emit::literal;
    let tyres: Vec<String> = spec
        .model
        .wheels
        .iter()
        .map(|w| {
            let t = w.tyre();
            format!(
                "::rover_dynamics::wheel_law::Tyre {{ stiffness: {}, damping: {}, mu_x: {}, \
                 mu_y: {}, cornering_stiffness: {}, rolling_resistance: {} }}",
                literal(t.stiffness),
                literal(t.damping),
                literal(t.mu_x),
                literal(t.mu_y),
                literal(t.cornering_stiffness),
                literal(t.rolling_resistance)
            )
        })
        .collect();
    let radii: Vec<String> = spec
        .model
        .wheels
        .iter()
        .map(|w| literal(w.radius))
        .collect();
    format!(
        r#"
    /// Each wheel's tyre, in the description's order: stiffness k_w,
    /// damping c_w, friction limits, cornering stiffness; no rolling
    /// resistance (a copy with `rolling_resistance` set adds it).
    pub const TYRES: [::rover_dynamics::wheel_law::Tyre; {k}] = [{tyres}];
    /// Each wheel's radius R_w [m], in the description's order.
    pub const RADII: [f64; {k}] = [{radii}];

    /// The ground under this rover's wheels, searched by `search`, for
    /// [`Self::derivatives_on_ground`]; it keeps what each wheel's search
    /// proved between calls (a few kilobytes per wheel, no heap).
    pub fn ground(search: {GROUND}::Search) -> {GROUND}::FixedGround<{k}> {{
        {GROUND}::FixedGround::new(search)
    }}

    /// The whole right-hand side on the ground `terrain`, as the runtime
    /// computes it with the generic plant: the wheels' kinematics for the
    /// steering angles `steer`, each wheel's contact, the motor torques
    /// `torques(normals)` [N·m] chosen from the wheels' normal forces \[N\]
    /// (a controller that shares torque by load reads them; an open-loop
    /// rig ignores them), the wheel law `law` on every patch with the
    /// tyres `tyres` (`&Self::TYRES`, a constant the compiler folds in),
    /// their reduction to loads, and `ẋ`, `ẇ`. The contact search and the
    /// law are `rover_dynamics::wheel_ground`'s, the code the generic
    /// plant's runs use; what each wheel did is in `ground.reports()`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn derivatives_on_ground<H, L>(
        &self,
        ground: &mut {GROUND}::FixedGround<{k}>,
        terrain: &H,
        law: &L,
        tyres: &[::rover_dynamics::wheel_law::Tyre; {k}],
        x: &[f64; {n}],
        w: &[f64; {n}],
        steer: &[f64; {k}],
        torques: impl FnOnce(&[f64; {k}]) -> [f64; {k}],
        xdot: &mut [f64; {n}],
        wdot: &mut [f64; {n}],
    ) -> ::core::result::Result<(), {GROUND}::GroundError>
    where
        H: ::rover_dynamics::HeightField + ?Sized,
        L: ::rover_dynamics::wheel_law::WheelLaw,
    {{
        let states = self.wheels_array(x, w, steer);
        let normals = ground
            .find_contacts(terrain, &states, tyres, &Self::RADII)
            .map_err({GROUND}::GroundError::OffMap)?;
        let torques = torques(normals);
        let loads = *ground.loads(law, &states, tyres, &torques);
        self.derivatives_array(x, w, &loads, xdot, wdot)
            .map_err({GROUND}::GroundError::Plant)
    }}
"#,
        tyres = tyres.join(", "),
        radii = radii.join(", "),
    )
}

/// Text from the description made safe for a one-line comment.
fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
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

fn emit_fn(f: &Function, comments: bool) -> (String, OpCount) {
    let (blocks, ops) = emit(&simplify(f), LIBM);
    (body(&blocks, comments), ops)
}

fn str_list(items: &[String]) -> String {
    let quoted: Vec<String> = items.iter().map(|s| format!("{s:?}")).collect();
    quoted.join(", ")
}

/// The plant type for `spec`.
pub fn plant_source(spec: &Spec, options: &Options) -> PlantSource {
    let traced: Traced = trace_spec_at(spec, options.jacobian, options.level.as_ref());
    let model = &spec.model;
    let (n, m, k) = (model.dof(), model.m(), model.wheels.len());
    let name = &options.type_name;
    let vis = &options.visibility;
    let c = options.comments;
    // Simplified once: emitted as scalar code, or planned in four lanes.
    let derivatives = simplify(&traced.derivatives);
    let (deriv_blocks, deriv_ops) = emit(&derivatives, LIBM);
    let deriv = body(&deriv_blocks, c);
    // The parameters of `derivatives_array` and of the copies behind it.
    let rhs_sig = format!(
        "(&self, x: &[f64; {n}], w: &[f64; {n}], loads: &[{PLANT}::WheelLoad; {k}], \
         xdot: &mut [f64; {n}], wdot: &mut [f64; {n}]) \
         -> ::core::result::Result<(), {PLANT}::PlantError> {{"
    );
    let all_positive = traced
        .pivot_rows
        .iter()
        .map(|r| format!("(pivot_{r} > 0.0)"))
        .collect::<Vec<_>>()
        .join(" & ");
    let pivots = traced
        .pivot_rows
        .iter()
        .map(|r| format!("({r}, pivot_{r}, pivot_den_{r})"))
        .collect::<Vec<_>>()
        .join(", ");
    // After the outputs: the checks the generic plant makes too.
    let tail = format!(
        r#"
        if f64::abs(cos_roll) < Self::MIN_COS_ROLL {{
            return Err({PLANT}::PlantError::AttitudeSingular {{ roll: x[3] }});
        }}
        // Each pivot is a ratio whose denominator the earlier checks made
        // positive: its numerator's sign decides. One test for all of them
        // (`&`, not `&&`: one branch; false for NaN), and the error, which
        // divides the failing value out to report it, built out of line.
        if {all_positive} {{
            return Ok(());
        }}
        Self::singular_mass([{pivots}])"#
    );
    // A four-wheeled rover's per-wheel work in four-lane operations, one
    // statement list printed for each copy; otherwise one scalar body
    // that both copies inline. Each input's lane is recorded by the trace.
    let seeds = lanes::seeds(&derivatives, |k| derivatives.inputs[k].lane.clone());
    let (v4_body, portable_body, body_fn, lane_note) = match lanes::plan(&derivatives, &seeds) {
        Some(plan) => (
            format!("{}{tail}", lanes::emit(&derivatives, &plan, true, LIBM)),
            format!("{}{tail}", lanes::emit(&derivatives, &plan, false, LIBM)),
            String::new(),
            Some(format!(
                "{} four-lane operations ({} of {} scalar ones), {} sums over the lanes",
                plan.vector_ops(),
                plan.packed_ops,
                plan.total_ops,
                plan.lane_sums()
            )),
        ),
        None => (
            "self.derivatives_body(x, w, loads, xdot, wdot)".to_string(),
            "self.derivatives_body(x, w, loads, xdot, wdot)".to_string(),
            format!(
                r#"
    /// The body of both copies, inlined into each so that each is compiled
    /// for its own instruction set.
    #[inline(always)]
    fn derivatives_body{rhs_sig}
        {deriv}{tail}
    }}
"#
            ),
            None,
        ),
    };
    let (mass, mass_ops) = emit_fn(&traced.mass_matrix, c);
    let (wheels, wheel_ops) = emit_fn(&traced.wheels, c);
    let mut ops = vec![
        ("derivatives", deriv_ops),
        ("mass_matrix", mass_ops),
        ("wheels", wheel_ops),
    ];
    let neutrals: Vec<String> = model
        .coordinates
        .iter()
        .map(|c| crate::emit::literal(c.neutral))
        .collect();
    let steer_used = model.wheels.iter().any(|w| w.steerable);
    let steer_param = if steer_used { "steer" } else { "_steer" };
    let coords_doc: Vec<String> = spec
        .coordinate_names
        .iter()
        .enumerate()
        .map(|(i, c)| format!("y{} `{c}`", i + 1))
        .collect();
    let mut s = String::new();
    let _ = write!(
        s,
        r#"
/// The `{rover}` rover as a generated plant: {n} degrees of freedom
/// (X, Y, Z, φ, θ, ψ, {coords}), {k} wheels ({wheel_list}).
///
/// Straight-line code traced from the equations of `rover-dynamics` with
/// this rover's constants folded in; no heap, no panics, `no_std`.
#[derive(Clone, Copy, Debug, PartialEq)]
{vis} struct {name} {{
    neutral: [f64; {m}],
}}

impl ::core::default::Default for {name} {{
    fn default() -> Self {{
        Self::new()
    }}
}}

#[allow(clippy::all, clippy::pedantic, unused_variables)]
impl {name} {{
    /// The rover's name in its description.
    pub const NAME: &'static str = {rover:?};
    /// Number of generalized coordinates N = 6 + m.
    pub const DOF: usize = {n};
    /// Number of wheels.
    pub const WHEELS: usize = {k};
    /// Names of the suspension coordinates y1 … ym.
    pub const COORDINATES: [&'static str; {m}] = [{coords_list}];
    /// Names of the wheels, in the description's order.
    pub const WHEEL_NAMES: [&'static str; {k}] = [{wheel_list_q}];
    /// The description's spring neutrals y_0.
    pub const SPRING_NEUTRALS: [f64; {m}] = [{neutrals}];
    /// Smallest |cos φ| accepted before the attitude is singular (as the generic plant).
    pub const MIN_COS_ROLL: f64 = {PLANT}::MIN_COS_ROLL;

    /// The plant with the description's spring neutrals.
    pub const fn new() -> Self {{
        Self {{ neutral: Self::SPRING_NEUTRALS }}
    }}

    /// The current spring neutrals y_0.
    pub fn spring_neutrals(&self) -> &[f64; {m}] {{
        &self.neutral
    }}

    /// `ẋ = B·w` and `ẇ = M⁻¹·(−Ṁ·w − f1 + f2 + Q)` (MODEL.md §5) on
    /// plain arrays ([`{PLANT}::FixedPlant::derivatives_fixed`] is the
    /// same on nalgebra vectors). The outputs are written in any case; the error says
    /// the attitude is singular (|cos φ| < 1e-6) or M is not positive
    /// definite (an LDLᵀ pivot not > 0), as the generic plant does; the
    /// suspension rows are eliminated first, so a failing pivot is checked
    /// in that order and reported with its row of M.
    ///
    /// On x86-64 the body is compiled twice, for the crate's target and for
    /// x86-64-v4, and each call takes the second when the processor has it
    /// ([`::rover_dynamics::cpu`]): the same operations, the same bits.
    #[inline]
    pub fn derivatives_array{rhs_sig}
        #[cfg(target_arch = "x86_64")]
        if ::rover_dynamics::cpu::x86_64_v4() {{
            // SAFETY: the processor has the features `derivatives_v4` is
            // compiled for.
            return unsafe {{ self.derivatives_v4(x, w, loads, xdot, wdot) }};
        }}
        self.derivatives_portable(x, w, loads, xdot, wdot)
    }}

    /// [`Self::derivatives_array`] compiled for x86-64-v4 (AVX-512: 32
    /// vector registers, so the straight-line body spills less); called
    /// only when [`::rover_dynamics::cpu::x86_64_v4`] finds those features.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "{V4_FEATURES}")]
    fn derivatives_v4{rhs_sig}
        {v4_body}
    }}

    /// [`Self::derivatives_array`] for the crate's own target only,
    /// whatever the processor offers (the reference of the tests that hold
    /// the two copies to the same bits). Out of line, as the one function
    /// its callers share: inlined, the body would be copied into each.
    #[doc(hidden)]
    #[inline(never)]
    pub fn derivatives_portable{rhs_sig}
        {portable_body}
    }}
{body_fn}
    /// The first pivot (row, numerator, denominator) whose numerator is not
    /// > 0, as the error; out of line, so that the pivots are not stored
    /// on the way to `Ok` (M is positive definite on every sane state).
    #[cold]
    #[inline(never)]
    fn singular_mass(
        pivots: [(usize, f64, f64); {n}],
    ) -> ::core::result::Result<(), {PLANT}::PlantError> {{
        for (row, num, den) in pivots {{
            if num.is_nan() || num <= 0.0 {{
                return Err({PLANT}::PlantError::SingularMass {{ row, pivot: num / den }});
            }}
        }}
        Ok(())
    }}

    /// The mass matrix M(y) (MODEL.md §4) as rows; structural zeros are
    /// not computed.
    #[inline]
    pub fn mass_matrix_array(&self, x: &[f64; {n}]) -> [[f64; {n}]; {n}] {{
        let mut m = [[0.0; {n}]; {n}];
        {mass}
        m
    }}

    /// Wheel-centre kinematics for the steering angles `steer` (ignored for
    /// wheels that are not steerable), MODEL.md §3, on plain arrays.
    #[inline]
    pub fn wheels_array(
        &self,
        x: &[f64; {n}],
        w: &[f64; {n}],
        {steer_param}: &[f64; {k}],
    ) -> [{PLANT}::WheelState; {k}] {{
        let mut out = [{PLANT}::WheelState {{ centre: [0.0; 3], velocity: [0.0; 3], spin_axis: [0.0; 3] }}; {k}];
        {wheels}
        out
    }}
"#,
        rover = one_line(&spec.name),
        coords = one_line(&coords_doc.join(", ")),
        wheel_list = one_line(&spec.wheel_names.join(", ")),
        coords_list = str_list(&spec.coordinate_names),
        wheel_list_q = str_list(&spec.wheel_names),
        neutrals = neutrals.join(", "),
    );
    if let Some(jac) = &traced.jacobian {
        let (code, jac_ops) = emit_fn(jac, c);
        ops.push(("jacobian", jac_ops));
        let two_n = 2 * n;
        let _ = write!(
            s,
            r#"
    /// The exact Jacobian `∂(ẋ, ẇ)/∂(x, w)` at fixed wheel loads,
    /// `jac[i][j] = ∂f_i/∂s_j` with `f = [ẋ; ẇ]`, `s = [x; w]`
    /// (symbolic differentiation of the traced equations), as rows.
    #[inline]
    pub fn jacobian_array(
        &self,
        x: &[f64; {n}],
        w: &[f64; {n}],
        loads: &[{PLANT}::WheelLoad; {k}],
    ) -> [[f64; {two_n}]; {two_n}] {{
        let mut jac = [[0.0; {two_n}]; {two_n}];
        {code}
        jac
    }}

    /// The exact Jacobian `∂(ẋ, ẇ)/∂(x, w)` at fixed wheel loads as a
    /// nalgebra matrix, `jac[(i, j)] = ∂f_i/∂s_j`.
    #[inline]
    pub fn jacobian_fixed(
        &self,
        x: &{NA}::SVector<f64, {n}>,
        w: &{NA}::SVector<f64, {n}>,
        loads: &[{PLANT}::WheelLoad; {k}],
    ) -> {NA}::SMatrix<f64, {two_n}, {two_n}> {{
        let rows = self.jacobian_array(&x.data.0[0], &w.data.0[0], loads);
        // nalgebra stores columns: the rows read as columns are the transpose.
        {NA}::SMatrix::from_array_storage({NA}::ArrayStorage(rows)).transpose()
    }}
"#
        );
    }
    s.push_str(&ground_methods(spec, n, k));
    s.push_str("}\n");
    let jacobian_method = if traced.jacobian.is_some() {
        format!(
            r#"
    fn jacobian(
        &mut self,
        x: &[f64],
        w: &[f64],
        loads: &[{PLANT}::WheelLoad],
        jac: &mut [f64],
    ) -> ::core::option::Option<()> {{
        let (Ok(x), Ok(w), Ok(loads)) = (
            <&[f64; {n}]>::try_from(x),
            <&[f64; {n}]>::try_from(w),
            <&[{PLANT}::WheelLoad; {k}]>::try_from(loads),
        ) else {{
            return None;
        }};
        for (o, v) in jac.iter_mut().zip(self.jacobian_array(x, w, loads).iter().flatten()) {{
            *o = *v;
        }}
        Some(())
    }}
"#
        )
    } else {
        String::new()
    };
    let _ = write!(
        s,
        r#"
/// Slices of the wrong length are not a panic: the outputs are filled with
/// NaN (the runtime's finiteness check then stops the run). Missing
/// steering angles and wheel loads count as zero, as in the generic plant.
impl {PLANT}::Plant for {name} {{
    fn dof(&self) -> usize {{
        {n}
    }}

    fn wheel_count(&self) -> usize {{
        {k}
    }}

    fn wheels(&mut self, x: &[f64], w: &[f64], steer: &[f64], out: &mut [{PLANT}::WheelState]) {{
        let (Ok(x), Ok(w)) = (<&[f64; {n}]>::try_from(x), <&[f64; {n}]>::try_from(w)) else {{
            let nan = [f64::NAN; 3];
            for o in out.iter_mut() {{
                *o = {PLANT}::WheelState {{ centre: nan, velocity: nan, spin_axis: nan }};
            }}
            return;
        }};
        let mut angles = [0.0; {k}];
        for (a, s) in angles.iter_mut().zip(steer) {{
            *a = *s;
        }}
        // The usual call, one state per wheel, gets the states written in
        // place instead of copied element by element (swing4: 765 → 729
        // instructions per call, callgrind).
        if let Ok(out) = <&mut [{PLANT}::WheelState; {k}]>::try_from(&mut *out) {{
            *out = self.wheels_array(x, w, &angles);
            return;
        }}
        for (o, s) in out.iter_mut().zip(self.wheels_array(x, w, &angles)) {{
            *o = s;
        }}
    }}

    fn derivatives(
        &mut self,
        x: &[f64],
        w: &[f64],
        loads: &[{PLANT}::WheelLoad],
        xdot: &mut [f64],
        wdot: &mut [f64],
    ) -> ::core::result::Result<(), {PLANT}::PlantError> {{
        let (Ok(x), Ok(w), Ok(xdot), Ok(wdot)) = (
            <&[f64; {n}]>::try_from(x),
            <&[f64; {n}]>::try_from(w),
            <&mut [f64; {n}]>::try_from(&mut *xdot),
            <&mut [f64; {n}]>::try_from(&mut *wdot),
        ) else {{
            xdot.iter_mut().chain(wdot.iter_mut()).for_each(|v| *v = f64::NAN);
            return Ok(());
        }};
        if let Ok(loads) = <&[{PLANT}::WheelLoad; {k}]>::try_from(loads) {{
            return self.derivatives_array(x, w, loads, xdot, wdot);
        }}
        let zero = {PLANT}::WheelLoad {{ force: [0.0; 3], moment: [0.0; 3], stator_torque: [0.0; 3] }};
        let mut fixed = [zero; {k}];
        for (f, l) in fixed.iter_mut().zip(loads) {{
            *f = *l;
        }}
        self.derivatives_array(x, w, &fixed, xdot, wdot)
    }}

    fn mass_matrix(&mut self, x: &[f64], out: &mut [f64]) {{
        let Ok(x) = <&[f64; {n}]>::try_from(x) else {{
            out.iter_mut().for_each(|v| *v = f64::NAN);
            return;
        }};
        let m = self.mass_matrix_array(x);
        for (o, v) in out.iter_mut().zip(m.iter().flatten()) {{
            *o = *v;
        }}
    }}

    fn set_spring_neutral(&mut self, coord: usize, neutral: f64) {{
        if let Some(n) = self.neutral.get_mut(coord) {{
            *n = neutral;
        }}
    }}
{jacobian_method}}}
"#
    );
    let _ = write!(
        s,
        r#"
/// The same plant on nalgebra's fixed-size types (no length checks, no heap).
impl {PLANT}::FixedPlant<{n}, {k}> for {name} {{
    #[inline]
    fn derivatives_fixed(
        &self,
        x: &{NA}::SVector<f64, {n}>,
        w: &{NA}::SVector<f64, {n}>,
        loads: &[{PLANT}::WheelLoad; {k}],
        xdot: &mut {NA}::SVector<f64, {n}>,
        wdot: &mut {NA}::SVector<f64, {n}>,
    ) -> ::core::result::Result<(), {PLANT}::PlantError> {{
        self.derivatives_array(
            &x.data.0[0],
            &w.data.0[0],
            loads,
            &mut xdot.data.0[0],
            &mut wdot.data.0[0],
        )
    }}

    #[inline]
    fn mass_matrix_fixed(&self, x: &{NA}::SVector<f64, {n}>) -> {NA}::SMatrix<f64, {n}, {n}> {{
        // M is symmetric: its rows are its columns.
        {NA}::SMatrix::from_array_storage({NA}::ArrayStorage(self.mass_matrix_array(&x.data.0[0])))
    }}

    #[inline]
    fn wheels_fixed(
        &self,
        x: &{NA}::SVector<f64, {n}>,
        w: &{NA}::SVector<f64, {n}>,
        steer: &{NA}::SVector<f64, {k}>,
    ) -> [{PLANT}::WheelState; {k}] {{
        self.wheels_array(&x.data.0[0], &w.data.0[0], &steer.data.0[0])
    }}
}}
"#
    );
    PlantSource {
        code: s,
        ops,
        lanes: lane_note,
    }
}
