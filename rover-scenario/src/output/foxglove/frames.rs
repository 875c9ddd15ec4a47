//! The rover's frames at one row: `world` → `body` → each suspension
//! member → each wheel, as `foxglove.FrameTransforms`.
//!
//! The members and their joints are the rover's sketch
//! ([`rover_spec::sketch`], what `rover drive`'s page draws): a member's
//! frame has its origin at the first joint of its first link and turns
//! with that link, by the shortest rotation from the link's direction at
//! the rest coordinates to its direction at the row's (a member that
//! swings about one pivot axis, as every library member does, turns by
//! exactly its swing). At rest a member's axes are the body's. A wheel's
//! frame is at the row's wheel centre, turned by its steering angle about
//! the body's z axis; its parent is the member that carries it (the body
//! for a suspension given as raw polynomials, which has no sketch).
//!
//! The body's rotation is R = Rz(ψ)·Rx(φ)·Ry(θ) (MODEL.md §1), its origin G
//! at (X, Y, Z): the transform `world` → `body` is the row's pose.

use foxglove::messages::{FrameTransform, FrameTransforms, Quaternion, Timestamp, Vector3};
use nalgebra::{UnitQuaternion, Vector3 as V3};
use rover_spec::Spec;
use rover_spec::sketch::Sketch;

/// The world frame's id.
pub const WORLD: &str = "world";
/// The body frame's id.
pub const BODY: &str = "body";

/// One member of a suspension: its frame and the links it draws.
#[derive(Clone, Debug)]
pub struct Member {
    /// Its frame's id, `<suspension>/<member>`.
    pub frame: String,
    /// The joint at its frame's origin (index into the sketch's joints).
    pub origin: usize,
    /// The joint its direction is taken to.
    pub toward: usize,
    /// The link's direction at rest, body axes (unit).
    rest_direction: V3<f64>,
    /// Its links' ends at rest, in its own frame \[m\].
    pub rods: Vec<[[f64; 3]; 2]>,
}

/// A row's column indices the frames read.
#[derive(Clone, Debug)]
struct Indices {
    pose: [usize; 6],
    coordinates: Vec<usize>,
    wheels: Vec<[usize; 3]>,
    steering: Vec<Option<usize>>,
}

/// The frames of one rover, computed from its rows into one message
/// reused from row to row.
#[derive(Clone, Debug)]
pub struct RoverFrames {
    sketch: Sketch,
    members: Vec<Member>,
    /// Each wheel's frame id, `wheel/<name>`.
    wheels: Vec<String>,
    /// The member each wheel hangs from (None: the body).
    wheel_parent: Vec<Option<usize>>,
    columns: Indices,
    message: FrameTransforms,
    /// Scratch: the row's suspension coordinates, the members' rotations.
    y: Vec<f64>,
    rotations: Vec<UnitQuaternion<f64>>,
    origins: Vec<V3<f64>>,
}

/// A row without a column the frames need.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("the row has no column `{0}`: not a row of this rover")]
pub struct MissingColumn(pub String);

/// The body's rotation R = Rz(ψ)·Rx(φ)·Ry(θ) (MODEL.md §1).
pub fn attitude(phi: f64, theta: f64, psi: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&V3::z_axis(), psi)
        * UnitQuaternion::from_axis_angle(&V3::x_axis(), phi)
        * UnitQuaternion::from_axis_angle(&V3::y_axis(), theta)
}

/// Simulated time as a message's timestamp (time 0 is the epoch);
/// negative or non-finite times are 0.
pub fn timestamp(t: f64) -> Timestamp {
    let ns = nanoseconds(t);
    Timestamp::new((ns / 1_000_000_000) as u32, (ns % 1_000_000_000) as u32)
}

/// Simulated time in nanoseconds, as the MCAP log and the live channels
/// stamp their messages.
pub fn nanoseconds(t: f64) -> u64 {
    if t.is_finite() && t > 0.0 {
        (t * 1e9).round() as u64
    } else {
        0
    }
}

fn vector(v: &V3<f64>) -> Vector3 {
    Vector3 {
        x: v.x,
        y: v.y,
        z: v.z,
    }
}

fn quaternion(q: &UnitQuaternion<f64>) -> Quaternion {
    Quaternion {
        x: q.i,
        y: q.j,
        z: q.k,
        w: q.w,
    }
}

fn transform(parent: &str, child: &str) -> FrameTransform {
    FrameTransform {
        timestamp: Some(timestamp(0.0)),
        parent_frame_id: parent.to_string(),
        child_frame_id: child.to_string(),
        translation: Some(Vector3::default()),
        rotation: Some(Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 1.0,
        }),
    }
}

impl RoverFrames {
    /// The frames of `spec`'s rover, read from rows of the columns `names`.
    pub fn new(spec: &Spec, names: &[String]) -> Result<Self, MissingColumn> {
        let find = |name: &str| {
            names
                .iter()
                .position(|n| n == name)
                .ok_or_else(|| MissingColumn(name.to_string()))
        };
        let pose = [
            find("X")?,
            find("Y")?,
            find("Z")?,
            find("phi")?,
            find("theta")?,
            find("psi")?,
        ];
        let m = spec.model.m();
        let coordinates = (1..=m)
            .map(|i| find(&format!("y{i}")))
            .collect::<Result<Vec<_>, _>>()?;
        let k = spec.model.wheels.len();
        let wheel_columns = (1..=k)
            .map(|j| {
                Ok([
                    find(&format!("W{j}X"))?,
                    find(&format!("W{j}Y"))?,
                    find(&format!("W{j}Z"))?,
                ])
            })
            .collect::<Result<Vec<_>, MissingColumn>>()?;
        let steering = (1..=k).map(|j| find(&format!("delta{j}")).ok()).collect();
        let sketch = spec.sketch.clone();
        let rest = spec.model.rest();
        let at_rest = sketch.positions(&rest);
        // One frame per (suspension, member), placed by its first link.
        let mut members: Vec<Member> = Vec::new();
        for link in &sketch.links {
            let frame = format!("{}/{}", link.suspension, link.member);
            let i = match members.iter().position(|m| m.frame == frame) {
                Some(i) => i,
                None => {
                    let [a, b] = link.joints;
                    let d = V3::from(at_rest[b]) - V3::from(at_rest[a]);
                    let norm = d.norm();
                    members.push(Member {
                        frame,
                        origin: a,
                        toward: b,
                        rest_direction: if norm > 0.0 { d / norm } else { V3::x() },
                        rods: Vec::new(),
                    });
                    members.len() - 1
                }
            };
            let o = at_rest[members[i].origin];
            let rel = |p: [f64; 3]| [p[0] - o[0], p[1] - o[1], p[2] - o[2]];
            let rod = [rel(at_rest[link.joints[0]]), rel(at_rest[link.joints[1]])];
            members[i].rods.push(rod);
        }
        let wheel_parent: Vec<Option<usize>> = (0..k)
            .map(|w| {
                let joint = sketch.joints.iter().position(|j| j.wheel == Some(w))?;
                let link = sketch.links.iter().find(|l| l.joints.contains(&joint))?;
                let frame = format!("{}/{}", link.suspension, link.member);
                members.iter().position(|m| m.frame == frame)
            })
            .collect();
        let wheels: Vec<String> = spec
            .wheel_names
            .iter()
            .map(|n| format!("wheel/{n}"))
            .collect();
        let mut transforms = vec![transform(WORLD, BODY)];
        transforms.extend(members.iter().map(|m| transform(BODY, &m.frame)));
        transforms.extend(
            wheels
                .iter()
                .zip(&wheel_parent)
                .map(|(w, p)| transform(p.map_or(BODY, |i| members[i].frame.as_str()), w)),
        );
        Ok(RoverFrames {
            y: vec![0.0; m],
            rotations: vec![UnitQuaternion::identity(); members.len()],
            origins: vec![V3::zeros(); members.len()],
            sketch,
            members,
            wheels,
            wheel_parent,
            columns: Indices {
                pose,
                coordinates,
                wheels: wheel_columns,
                steering,
            },
            message: FrameTransforms { transforms },
        })
    }

    /// The members, in the order of their transforms (after the body's).
    pub fn members(&self) -> &[Member] {
        &self.members
    }

    /// Each wheel's frame id.
    pub fn wheel_frames(&self) -> &[String] {
        &self.wheels
    }

    /// The member each wheel hangs from (None: the body).
    pub fn wheel_parents(&self) -> &[Option<usize>] {
        &self.wheel_parent
    }

    /// The transforms at the row `row` (of the columns given to
    /// [`RoverFrames::new`]), stamped with its time `t`. Allocates
    /// nothing: the message is updated in place.
    pub fn update(&mut self, t: f64, row: &[f64]) -> &FrameTransforms {
        let c = &self.columns;
        let p = c.pose.map(|i| row[i]);
        let body = attitude(p[3], p[4], p[5]);
        let g = V3::new(p[0], p[1], p[2]);
        let inverse = body.inverse();
        for (y, &i) in self.y.iter_mut().zip(&c.coordinates) {
            *y = row[i];
        }
        let stamp = timestamp(t);
        let set = |tf: &mut FrameTransform, at: &V3<f64>, q: &UnitQuaternion<f64>| {
            tf.timestamp = Some(stamp);
            tf.translation = Some(vector(at));
            tf.rotation = Some(quaternion(q));
        };
        let tfs = &mut self.message.transforms;
        set(&mut tfs[0], &g, &body);
        for (k, m) in self.members.iter().enumerate() {
            let a = V3::from(self.sketch.joints[m.origin].position.value(&self.y));
            let b = V3::from(self.sketch.joints[m.toward].position.value(&self.y));
            let turn = UnitQuaternion::rotation_between(&m.rest_direction, &(b - a))
                .unwrap_or_else(UnitQuaternion::identity);
            self.rotations[k] = turn;
            self.origins[k] = a;
            set(&mut tfs[1 + k], &a, &turn);
        }
        let first_wheel = 1 + self.members.len();
        for (j, w) in c.wheels.iter().enumerate() {
            // The row's centre in body axes: the wheel frame lands on the
            // CSV's W{j}.
            let centre = inverse * (V3::new(row[w[0]], row[w[1]], row[w[2]]) - g);
            let delta = c.steering[j].map_or(0.0, |i| row[i]);
            let steer = UnitQuaternion::from_axis_angle(&V3::z_axis(), delta);
            let (at, q) = match self.wheel_parent[j] {
                Some(k) => {
                    let back = self.rotations[k].inverse();
                    (back * (centre - self.origins[k]), back * steer)
                }
                None => (centre, steer),
            };
            set(&mut tfs[first_wheel + j], &at, &q);
        }
        &self.message
    }
}
