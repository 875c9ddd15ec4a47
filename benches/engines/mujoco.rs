//! MuJoCo, loaded at run time from the shared library a `pip install
//! mujoco` brings (its C API through `libloading`: no build-time link, no
//! header), and a rover description written as MJCF.
//!
//! Only the functions the comparison needs are bound; every one of them
//! is in MuJoCo's stable C API (`mujoco.h`, 3.x). Model and data are freed
//! on drop.

use std::ffi::{CStr, CString, c_char, c_int, c_uint, c_void};
use std::path::Path;

use rover_dynamics::model::Spring;
use rover_runtime::terrain::Grid;
use rover_spec::Spec;
use rover_spec::description::SuspensionDesc;

type LoadXml =
    unsafe extern "C" fn(*const c_char, *const c_void, *mut c_char, c_int) -> *mut c_void;
type MakeData = unsafe extern "C" fn(*const c_void) -> *mut c_void;
type Step = unsafe extern "C" fn(*const c_void, *mut c_void);
type ResetKey = unsafe extern "C" fn(*const c_void, *mut c_void, c_int);
type StateSize = unsafe extern "C" fn(*const c_void, c_uint) -> c_int;
type GetState = unsafe extern "C" fn(*const c_void, *const c_void, *mut f64, c_uint);
type Delete = unsafe extern "C" fn(*mut c_void);
type Version = unsafe extern "C" fn() -> *const c_char;

/// `mjSTATE_QPOS` (mjdata.h).
const STATE_QPOS: c_uint = 1 << 1;
/// `mjSTATE_QVEL`.
const STATE_QVEL: c_uint = 1 << 2;

/// The bound library.
pub struct Mujoco {
    // Kept alive for the function pointers below.
    _lib: libloading::Library,
    load_xml: LoadXml,
    make_data: MakeData,
    step: Step,
    forward: Step,
    reset_key: ResetKey,
    state_size: StateSize,
    get_state: GetState,
    delete_data: Delete,
    delete_model: Delete,
    version: Version,
}

impl Mujoco {
    /// Load `libmujoco.so.*` from `path`.
    pub fn load(path: &Path) -> Result<Self, String> {
        // SAFETY: loading runs the library's initializers; MuJoCo's only
        // set up its own globals.
        let lib = unsafe { libloading::Library::new(path) }
            .map_err(|e| format!("cannot load {}: {e}", path.display()))?;
        macro_rules! sym {
            ($name:literal) => {
                // SAFETY: the type is the function's C signature in mujoco.h.
                *unsafe { lib.get(concat!($name, "\0").as_bytes()) }
                    .map_err(|e| format!("{}: no `{}`: {e}", path.display(), $name))?
            };
        }
        Ok(Self {
            load_xml: sym!("mj_loadXML"),
            make_data: sym!("mj_makeData"),
            step: sym!("mj_step"),
            forward: sym!("mj_forward"),
            reset_key: sym!("mj_resetDataKeyframe"),
            state_size: sym!("mj_stateSize"),
            get_state: sym!("mj_getState"),
            delete_data: sym!("mj_deleteData"),
            delete_model: sym!("mj_deleteModel"),
            version: sym!("mj_versionString"),
            _lib: lib,
        })
    }

    /// MuJoCo's version string.
    pub fn version(&self) -> String {
        // SAFETY: a static NUL-terminated string.
        unsafe { CStr::from_ptr((self.version)()) }
            .to_string_lossy()
            .into_owned()
    }

    /// Compile the MJCF in `file`.
    pub fn model(&self, file: &Path, timestep: f64) -> Result<Sim<'_>, String> {
        let name = CString::new(file.to_string_lossy().as_bytes()).map_err(|e| e.to_string())?;
        let mut error = vec![0 as c_char; 1000];
        // SAFETY: valid C strings and an error buffer of the size given.
        let model =
            unsafe { (self.load_xml)(name.as_ptr(), std::ptr::null(), error.as_mut_ptr(), 1000) };
        if model.is_null() {
            // SAFETY: MuJoCo wrote a NUL-terminated message into the buffer.
            let msg = unsafe { CStr::from_ptr(error.as_ptr()) };
            return Err(format!("{}: {}", file.display(), msg.to_string_lossy()));
        }
        // SAFETY: a compiled model.
        let data = unsafe { (self.make_data)(model) };
        if data.is_null() {
            // SAFETY: the model was allocated by mj_loadXML.
            unsafe { (self.delete_model)(model) };
            return Err("mj_makeData failed".into());
        }
        Ok(Sim {
            mj: self,
            model,
            data,
            timestep,
        })
    }
}

/// A compiled model and its data.
pub struct Sim<'a> {
    mj: &'a Mujoco,
    model: *mut c_void,
    data: *mut c_void,
    timestep: f64,
}

impl Sim<'_> {
    /// From keyframe 0, `duration` [s] of the model's integrator.
    pub fn run(&mut self, duration: f64) {
        self.reset();
        for _ in 0..(duration / self.timestep).round() as usize {
            self.step();
        }
    }

    /// Back to keyframe 0 (the start: positions, velocities, controls).
    pub fn reset(&mut self) {
        // SAFETY: model and data belong together; keyframe 0 exists (see [`mjcf`]).
        unsafe { (self.mj.reset_key)(self.model, self.data, 0) }
    }

    /// One step of the model's integrator.
    pub fn step(&mut self) {
        // SAFETY: model and data belong together.
        unsafe { (self.mj.step)(self.model, self.data) }
    }

    /// Forward dynamics at the current state (positions, collisions,
    /// constraint forces, accelerations), no integration.
    pub fn forward(&mut self) {
        // SAFETY: model and data belong together.
        unsafe { (self.mj.forward)(self.model, self.data) }
    }

    /// `qpos` or `qvel`.
    fn state(&self, sig: c_uint) -> Vec<f64> {
        // SAFETY: model and data belong together; the buffer has the size
        // MuJoCo asks for this signature.
        unsafe {
            let n = (self.mj.state_size)(self.model, sig) as usize;
            let mut out = vec![0.0; n];
            (self.mj.get_state)(self.model, self.data, out.as_mut_ptr(), sig);
            out
        }
    }

    /// Generalized positions: the free joint's `[x, y, z, qw, qx, qy, qz]`,
    /// then per wheel, in the description's order, its arm's angle and its
    /// spin angle.
    pub fn qpos(&self) -> Vec<f64> {
        self.state(STATE_QPOS)
    }

    /// Generalized velocities: the free joint's `[v; ω]`, then per wheel
    /// its arm's rate and its spin rate.
    pub fn qvel(&self) -> Vec<f64> {
        self.state(STATE_QVEL)
    }
}

impl Drop for Sim<'_> {
    fn drop(&mut self) {
        // SAFETY: allocated by mj_makeData and mj_loadXML, freed once.
        unsafe {
            (self.mj.delete_data)(self.data);
            (self.mj.delete_model)(self.model);
        }
    }
}

/// How MuJoCo integrates, and the wheels' shape.
#[derive(Clone, Copy, Debug)]
pub struct Setup {
    /// MJCF's `integrator`: `Euler`, `RK4`, `implicitfast`.
    pub integrator: &'static str,
    /// Its step [s].
    pub timestep: f64,
    /// The wheel's geom: `cylinder` (the wheel's shape: up to four contacts
    /// with a plane) or `sphere` of the wheel's radius (one contact, the
    /// cheap stand-in MuJoCo models often use for wheels).
    pub wheel: &'static str,
}

/// Half-width of the wheels' cylinders [m] (a sphere ignores it). The description has no wheel
/// width (the paper's wheel is a disc touching along its rim).
pub const WHEEL_HALF_WIDTH: f64 = 0.02;

/// The rover of `spec` as MJCF, for rovers on longitudinal swing arms
/// (the paper's Example 2): the body (mass, full inertia tensor at G) on a
/// free joint, one hinge per arm about the body's y axis at its pivot,
/// `y = 0` hanging straight down, `u = A + Ry(y)·[0, 0, −l]` as MODEL.md §3,
/// with the description's spring (stiffness, neutral), damping and
/// travel; the wheel's mass on a cylinder of the wheel's radius at the
/// arm's end, spinning on a hinge about the arm's y axis; the paper's
/// massless arm weighs 1 µg (MuJoCo refuses a moving body without mass:
/// `boundmass`, `boundinertia`). The motors are MuJoCo's velocity servos on the spin hinges,
/// `τ = kv·(V/R − ω)` with `kv = kp·R` (the paper's P loop `τ = kp·(V −
/// v_x)` per wheel, with rolling `v_x = R·ω`), limited to `max_torque`.
/// Contact and friction are MuJoCo's own (its defaults, friction μ = the
/// wheels' `mu_x`): the wheel–ground law is the one thing the two engines
/// cannot share. Keyframe 0 is the start of [`crate::support::system`]:
/// G at `start_height`, the arms at their rest angles, at rest, the servos
/// at `speed`. The ground is the plane Z = 0, or `map`'s nodes as a
/// height field (MuJoCo triangulates each cell where rover interpolates
/// the same nodes bicubically).
pub fn mjcf(
    spec: &Spec,
    setup: Setup,
    map: Option<&Grid>,
    kp: f64,
    speed: f64,
    start_height: f64,
) -> Result<String, String> {
    let model = &spec.model;
    let d = &spec.description;
    let b = &model.body;
    let i = b.inertia;
    let mut bodies = String::new();
    let mut actuators = String::new();
    let mut qpos = format!("0 0 {start_height} 1 0 0 0");
    let mut ctrl = String::new();
    for (k, wheel) in model.wheels.iter().enumerate() {
        let wdesc = &d.wheels[k];
        let (s, arm) = d
            .suspensions
            .iter()
            .enumerate()
            .find_map(|(s, sd)| match sd {
                SuspensionDesc::LongitudinalSwingArm(a) if a.name == wdesc.suspension => {
                    Some((s, a))
                }
                _ => None,
            })
            .ok_or_else(|| {
                format!(
                    "wheel `{}`: only wheels on longitudinal swing arms are written as MJCF",
                    wdesc.name
                )
            })?;
        let c = spec.suspensions[s].coordinates[0];
        let coord = &model.coordinates[c];
        let stiffness = match coord.spring {
            Spring::Linear { stiffness } => stiffness,
            Spring::None => 0.0,
            Spring::Table { .. } => return Err(format!("`{}`: a table spring", arm.name)),
        };
        let mass = model.bodies[wheel.body].mass;
        let [px, py, pz] = arm.pivot;
        let (r, l) = (wheel.radius, arm.length);
        bodies.push_str(&format!(
            r#"      <body name="arm{k}" pos="{px} {py} {pz}">
        <joint name="y{k}" type="hinge" axis="0 1 0" stiffness="{stiffness}" springref="{neutral}" damping="{damping}" range="{min} {max}"/>
        <body name="wheel{k}" pos="0 0 {z}">
          <joint name="spin{k}" type="hinge" axis="0 1 0"/>
          <geom type="{shape}" size="{r} {hw}" zaxis="0 1 0" mass="{mass}" friction="{friction}"/>
        </body>
      </body>
"#,
            neutral = coord.neutral,
            damping = coord.damping,
            min = coord.min,
            max = coord.max,
            z = -l,
            hw = WHEEL_HALF_WIDTH,
            shape = setup.wheel,
            friction = friction(wheel.mu_x),
        ));
        actuators.push_str(&format!(
            "    <velocity joint=\"spin{k}\" kv=\"{kv}\" forcerange=\"{lo} {hi}\"/>\n",
            kv = kp * r,
            lo = -wheel.max_torque,
            hi = wheel.max_torque,
        ));
        qpos.push_str(&format!(" {} 0", coord.rest));
        ctrl.push_str(&format!(" {}", speed / r));
    }
    let mu = model.wheels.first().map_or(1.0, |w| w.mu_x);
    let (asset, ground) = match map {
        None => (
            String::new(),
            format!(
                r#"<geom name="ground" type="plane" size="0 0 1" friction="{f}"/>"#,
                f = friction(mu)
            ),
        ),
        Some(grid) => height_field(grid, mu)?,
    };
    Ok(format!(
        r#"<mujoco model="{name}">
  <compiler angle="radian" autolimits="true" boundmass="1e-6" boundinertia="1e-12"/>
  <option timestep="{dt}" integrator="{integrator}" gravity="0 0 {g}"/>
{asset}  <worldbody>
    {ground}
    <body name="body">
      <freejoint/>
      <inertial pos="0 0 0" mass="{mass}" fullinertia="{ixx} {iyy} {izz} {ixy} {ixz} {iyz}"/>
{bodies}    </body>
  </worldbody>
  <actuator>
{actuators}  </actuator>
  <keyframe>
    <key qpos="{qpos}" ctrl="{ctrl}"/>
  </keyframe>
</mujoco>
"#,
        name = d.name,
        dt = setup.timestep,
        integrator = setup.integrator,
        g = -model.gravity,
        mass = b.mass,
        ixx = i[0][0],
        iyy = i[1][1],
        izz = i[2][2],
        ixy = i[0][1],
        ixz = i[0][2],
        iyz = i[1][2],
        ctrl = ctrl.trim_start(),
    ))
}

/// MJCF's `friction` of a geom: sliding μ, MuJoCo's default torsional and
/// rolling friction.
fn friction(mu: f64) -> String {
    format!("{mu} 0.005 0.0001")
}

/// `grid` as an MJCF height-field asset and its geom. MuJoCo scales the
/// elevations to [0, 1] of the field's height above its geom, and its
/// first row is the map's largest Y (checked with `mj_ray` on a ramp).
fn height_field(grid: &Grid, mu: f64) -> Result<(String, String), String> {
    let (nx, ny) = (grid.nx(), grid.ny());
    let ([x0, y0], [hx, hy]) = (grid.origin(), grid.spacing());
    let heights = grid.heights();
    let lo = heights.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = heights.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if hi.is_nan() || hi <= lo {
        return Err("a height field needs relief: write flat ground as the plane".into());
    }
    let mut elevation = String::with_capacity(12 * nx * ny);
    for j in (0..ny).rev() {
        for z in &heights[j * nx..(j + 1) * nx] {
            elevation.push_str(&format!("{z} "));
        }
    }
    let (rx, ry) = ((nx - 1) as f64 * hx / 2.0, (ny - 1) as f64 * hy / 2.0);
    let asset = format!(
        "  <asset>\n    <hfield name=\"map\" nrow=\"{ny}\" ncol=\"{nx}\" size=\"{rx} {ry} {top} 0.1\" elevation=\"{e}\"/>\n  </asset>\n",
        top = hi - lo,
        e = elevation.trim_end(),
    );
    let geom = format!(
        r#"<geom name="ground" type="hfield" hfield="map" pos="{cx} {cy} {lo}" friction="{f}"/>"#,
        f = friction(mu),
        cx = x0 + rx,
        cy = y0 + ry,
    );
    Ok((asset, geom))
}
