//! What the 3D panel draws, as `foxglove.SceneUpdate`s: the rover (its
//! body box and heading arrow in `body`, each member's rods in its own
//! frame, each wheel a cylinder in its frame; every entity locked to its
//! frame, so that it moves with the transforms), and the terrain as a
//! triangle mesh in `world`, coloured by height.

use foxglove::messages::{
    ArrowPrimitive, Color, CubePrimitive, CylinderPrimitive, Point3, Pose, Quaternion, SceneEntity,
    SceneUpdate, TriangleListPrimitive, Vector3,
};
use nalgebra::{UnitQuaternion, Vector3 as V3};
use rover_spec::Spec;

use super::frames::{BODY, RoverFrames, WORLD, timestamp};
use crate::output::{HeightGrid, body_box};

fn color(r: f64, g: f64, b: f64, a: f64) -> Option<Color> {
    Some(Color { r, g, b, a })
}

fn pose(at: [f64; 3], q: UnitQuaternion<f64>) -> Option<Pose> {
    Some(Pose {
        position: Some(Vector3 {
            x: at[0],
            y: at[1],
            z: at[2],
        }),
        orientation: Some(Quaternion {
            x: q.i,
            y: q.j,
            z: q.k,
            w: q.w,
        }),
    })
}

fn entity(frame: &str, id: &str) -> SceneEntity {
    SceneEntity {
        timestamp: Some(timestamp(0.0)),
        frame_id: frame.to_string(),
        id: id.to_string(),
        // No lifetime: shown until replaced.
        lifetime: None,
        frame_locked: true,
        ..SceneEntity::default()
    }
}

/// A cylinder from `a` to `b` (a rod of diameter `d`): the primitive's
/// axis is its z.
fn rod(a: [f64; 3], b: [f64; 3], d: f64, c: Option<Color>) -> Option<CylinderPrimitive> {
    let (a, b) = (V3::from(a), V3::from(b));
    let along = b - a;
    let length = along.norm();
    if length < 1e-9 {
        return None;
    }
    let q = UnitQuaternion::rotation_between(&V3::z(), &along)
        .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&V3::x_axis(), std::f64::consts::PI));
    let mid = (a + b) / 2.0;
    Some(CylinderPrimitive {
        pose: pose([mid.x, mid.y, mid.z], q),
        size: Some(Vector3 {
            x: d,
            y: d,
            z: length,
        }),
        bottom_scale: 1.0,
        top_scale: 1.0,
        color: c,
    })
}

/// The rover's geometry, each part in its frame of `frames`.
pub fn rover_scene(spec: &Spec, frames: &RoverFrames) -> SceneUpdate {
    let model = &spec.model;
    let rest = model.rest_wheel_centres();
    let radius: Vec<f64> = model.wheels.iter().map(|w| w.radius).collect();
    let r_max = radius.iter().cloned().fold(0.0, f64::max);
    let [length, width, height] = body_box(&rest, &radius);
    let mut body = entity(BODY, "body");
    body.cubes.push(CubePrimitive {
        pose: pose([0.0; 3], UnitQuaternion::identity()),
        size: Some(Vector3 {
            x: length,
            y: width,
            z: height,
        }),
        color: color(0.85, 0.55, 0.2, 1.0),
    });
    // The heading: an arrow along body x from the box's front.
    body.arrows.push(ArrowPrimitive {
        pose: pose([length / 2.0, 0.0, 0.0], UnitQuaternion::identity()),
        shaft_length: 0.5 * height,
        shaft_diameter: 0.3 * height,
        head_length: 0.5 * height,
        head_diameter: 0.7 * height,
        color: color(0.75, 0.22, 0.17, 1.0),
    });
    let mut entities = vec![body];
    let rod_d = 0.16 * r_max;
    for m in frames.members() {
        let mut e = entity(&m.frame, &m.frame);
        e.cylinders.extend(
            m.rods
                .iter()
                .filter_map(|[a, b]| rod(*a, *b, rod_d, color(0.6, 0.82, 1.0, 1.0))),
        );
        entities.push(e);
    }
    // A wheel on no member (raw polynomial suspension): a line from the
    // body to its rest centre, as the page draws it.
    for ((frame, parent), (r, centre)) in frames
        .wheel_frames()
        .iter()
        .zip(frames.wheel_parents())
        .zip(radius.iter().zip(&rest))
    {
        let mut e = entity(frame, frame);
        // Axle along the wheel frame's y: the cylinder's z turned onto it.
        let axle = UnitQuaternion::from_axis_angle(&V3::x_axis(), std::f64::consts::FRAC_PI_2);
        e.cylinders.push(CylinderPrimitive {
            pose: pose([0.0; 3], axle),
            size: Some(Vector3 {
                x: 2.0 * r,
                y: 2.0 * r,
                z: 0.5 * r,
            }),
            bottom_scale: 1.0,
            top_scale: 1.0,
            color: color(0.2, 0.2, 0.2, 1.0),
        });
        e.cubes.push(CubePrimitive {
            pose: pose([0.0; 3], UnitQuaternion::identity()),
            size: Some(Vector3 {
                x: 1.6 * r,
                y: 0.52 * r,
                z: 0.25 * r,
            }),
            color: color(0.55, 0.55, 0.55, 1.0),
        });
        entities.push(e);
        if parent.is_none() {
            let mut link = entity(BODY, &format!("{frame}/link"));
            link.cylinders.extend(rod(
                [centre[0], centre[1], 0.0],
                *centre,
                0.5 * rod_d,
                color(0.6, 0.82, 1.0, 1.0),
            ));
            entities.push(link);
        }
    }
    SceneUpdate {
        deletions: Vec::new(),
        entities,
    }
}

/// The ground of `grid` as one triangle list in `world` (two triangles a
/// cell, the cells with a height at each corner), each node coloured by
/// its height from the grid's lowest (dark) to its highest (light).
pub fn terrain_scene(grid: &HeightGrid) -> SceneUpdate {
    let (nx, ny) = (grid.nx, grid.ny);
    let heights = grid.z.iter().flatten();
    let lo = heights.clone().cloned().fold(f64::INFINITY, f64::min);
    let hi = heights.cloned().fold(f64::NEG_INFINITY, f64::max);
    let span = if hi > lo { hi - lo } else { 1.0 };
    let mut points = Vec::with_capacity(nx * ny);
    let mut colors = Vec::with_capacity(nx * ny);
    let mut index = vec![u32::MAX; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            if let Some([x, y, z]) = grid.node(i, j) {
                index[j * nx + i] = points.len() as u32;
                points.push(Point3 { x, y, z });
                let s = 0.35 + 0.5 * (z - lo) / span;
                colors.push(Color {
                    r: s,
                    g: 0.85 * s,
                    b: 0.7 * s,
                    a: 1.0,
                });
            }
        }
    }
    let mut indices = Vec::with_capacity(6 * (nx - 1) * (ny - 1));
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let c = [
                index[j * nx + i],
                index[j * nx + i + 1],
                index[(j + 1) * nx + i + 1],
                index[(j + 1) * nx + i],
            ];
            if c.contains(&u32::MAX) {
                continue;
            }
            indices.extend_from_slice(&[c[0], c[1], c[2], c[0], c[2], c[3]]);
        }
    }
    let mut e = entity(WORLD, "terrain");
    e.frame_locked = false;
    e.triangles.push(TriangleListPrimitive {
        pose: pose([0.0; 3], UnitQuaternion::identity()),
        points,
        color: color(0.6, 0.5, 0.4, 1.0),
        colors,
        indices,
    });
    SceneUpdate {
        deletions: Vec::new(),
        entities: vec![e],
    }
}
