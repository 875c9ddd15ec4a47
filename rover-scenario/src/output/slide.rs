//! Sideways slides of a run: the yaw rate against its usual value and the
//! sideways speed of each axle over the ground, at output instants after
//! settling (the paper's passive rover, Fig. 15–16, "the rear wheels slide
//! suddenly to the right, causing an abrupt change of the yaw angle").

use serde::Serialize;

/// Window over which a sudden slide's yaw change is judged \[s\].
pub const SLIDE_WINDOW: f64 = 2.0;
/// A yaw change beyond the run's usual turning of at least this much within
/// [`SLIDE_WINDOW`] is a sudden slide \[deg\].
pub const SLIDE_YAW_DEG: f64 = 5.0;

/// The run's slide measures.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Slide {
    /// The usual yaw rate: the median over the output intervals \[deg/s\].
    pub median_yaw_rate_deg_s: f64,
    /// Largest |ψ̇ − median ψ̇| over an output interval \[deg/s\].
    pub max_yaw_rate_excursion_deg_s: f64,
    /// When it happened (the interval's middle) \[s\].
    pub max_yaw_rate_excursion_t: f64,
    /// Largest |Δψ − median ψ̇·Δt| over any [`SLIDE_WINDOW`] \[deg\].
    pub max_yaw_change_deg: f64,
    /// Each axle's sideways speed over the ground.
    pub axles: Vec<AxleSlide>,
    /// The first sudden slide, if any: a yaw change of at least
    /// [`SLIDE_YAW_DEG`] beyond the usual turning within [`SLIDE_WINDOW`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sudden: Option<SuddenSlide>,
}

/// One axle: the wheels sharing a rest x, and the sideways speed of their
/// centres' midpoint, horizontal and across the heading.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AxleSlide {
    /// The axle's wheels (1-based).
    pub wheels: Vec<usize>,
    /// Their rest x in body axes \[m\].
    pub rest_x: f64,
    /// Largest sideways speed, positive to the left [m/s].
    pub max_lateral_speed_m_s: f64,
    /// When it happened \[s\].
    pub max_lateral_speed_t: f64,
    /// RMS sideways speed [m/s].
    pub rms_lateral_speed_m_s: f64,
}

/// A detected sudden slide.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SuddenSlide {
    /// Time of the largest yaw-rate excursion in the first window whose yaw
    /// change reaches [`SLIDE_YAW_DEG`] \[s\].
    pub t: f64,
    /// G's horizontal position then \[m\].
    pub position: [f64; 2],
    /// G's path length from the end of settling to then \[m\].
    pub distance_m: f64,
    /// The window's yaw change beyond the usual turning, signed (positive:
    /// to the left) \[deg\].
    pub yaw_change_deg: f64,
    /// Index (0-based, in [`Slide::axles`]) of the axle sliding fastest in
    /// the window.
    pub axle: usize,
    /// Its largest sideways speed in the window, positive to the left [m/s].
    pub lateral_speed_m_s: f64,
}

/// What the slide measures read, one entry per output instant after settling.
pub struct SlideTrack<'a> {
    /// Times \[s\].
    pub times: &'a [f64],
    /// Yaw ψ \[rad\].
    pub yaw: &'a [f64],
    /// G's horizontal position \[m\].
    pub path: &'a [[f64; 2]],
    /// Per axle, its wheel centres' horizontal midpoint at each instant \[m\].
    pub axles: &'a [Vec<[f64; 2]>],
}

/// The slide measures of a track, for axles given as (wheels, rest x);
/// None with fewer than three instants.
pub fn slide(track: &SlideTrack, axles: &[(Vec<usize>, f64)]) -> Option<Slide> {
    let t = track.times;
    let n = t.len();
    if n < 3 {
        return None;
    }
    // Yaw rate over each interval, the angle difference wrapped to (−π, π].
    let rates: Vec<f64> = (1..n)
        .map(|k| {
            let d = track.yaw[k] - track.yaw[k - 1];
            d.sin().atan2(d.cos()) / (t[k] - t[k - 1])
        })
        .collect();
    let mut sorted = rates.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    let (k_max, excursion) = rates
        .iter()
        .map(|r| (r - median).abs())
        .enumerate()
        .fold((0, 0.0), |a, (k, e)| if e > a.1 { (k, e) } else { a });
    let lateral: Vec<Vec<f64>> = track
        .axles
        .iter()
        .map(|mid| {
            (1..n)
                .map(|k| {
                    let dt = t[k] - t[k - 1];
                    let (vx, vy) = (
                        (mid[k][0] - mid[k - 1][0]) / dt,
                        (mid[k][1] - mid[k - 1][1]) / dt,
                    );
                    let psi = 0.5 * (track.yaw[k] + track.yaw[k - 1]);
                    -psi.sin() * vx + psi.cos() * vy
                })
                .collect()
        })
        .collect();
    let axle_slides = axles
        .iter()
        .zip(&lateral)
        .map(|((wheels, x), l)| {
            let k = largest(l);
            AxleSlide {
                wheels: wheels.clone(),
                rest_x: *x,
                max_lateral_speed_m_s: l[k],
                max_lateral_speed_t: 0.5 * (t[k] + t[k + 1]),
                rms_lateral_speed_m_s: (l.iter().map(|v| v * v).sum::<f64>() / l.len() as f64)
                    .sqrt(),
            }
        })
        .collect();
    // Yaw change beyond the usual turning over each window from each instant.
    let mut cumulative = vec![0.0; n];
    for k in 1..n {
        cumulative[k] = cumulative[k - 1] + (rates[k - 1] - median) * (t[k] - t[k - 1]);
    }
    let mut max_change = 0.0f64;
    let mut sudden = None;
    for i in 0..n {
        let j = t.partition_point(|&s| s <= t[i] + SLIDE_WINDOW + 1e-9) - 1;
        if j <= i {
            continue;
        }
        let change = cumulative[j] - cumulative[i];
        max_change = max_change.max(change.abs());
        if sudden.is_none() && change.abs().to_degrees() >= SLIDE_YAW_DEG {
            let window = i..j;
            let k = window
                .clone()
                .max_by(|&a, &b| {
                    (rates[a] - median)
                        .abs()
                        .total_cmp(&(rates[b] - median).abs())
                })
                .unwrap_or(i);
            let (axle, speed) = lateral
                .iter()
                .enumerate()
                .map(|(a, l)| {
                    let m = window
                        .clone()
                        .map(|k| l[k])
                        .fold(0.0, |m: f64, v| if v.abs() > m.abs() { v } else { m });
                    (a, m)
                })
                .fold(
                    (0, 0.0f64),
                    |b, c| if c.1.abs() > b.1.abs() { c } else { b },
                );
            let distance: f64 = track.path[..=k + 1]
                .windows(2)
                .map(|p| (p[1][0] - p[0][0]).hypot(p[1][1] - p[0][1]))
                .sum();
            sudden = Some(SuddenSlide {
                t: 0.5 * (t[k] + t[k + 1]),
                position: track.path[k + 1],
                distance_m: distance,
                yaw_change_deg: change.to_degrees(),
                axle,
                lateral_speed_m_s: speed,
            });
        }
    }
    Some(Slide {
        median_yaw_rate_deg_s: median.to_degrees(),
        max_yaw_rate_excursion_deg_s: excursion.to_degrees(),
        max_yaw_rate_excursion_t: 0.5 * (t[k_max] + t[k_max + 1]),
        max_yaw_change_deg: max_change.to_degrees(),
        axles: axle_slides,
        sudden,
    })
}

/// Index of the largest |v|.
fn largest(v: &[f64]) -> usize {
    (0..v.len())
        .max_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
        .unwrap_or(0)
}

/// Wheels grouped into axles by rest x (within 1 cm), front first: each
/// axle's wheels (1-based) and mean rest x.
pub fn axles_by_rest_x(rest_x: &[f64]) -> Vec<(Vec<usize>, f64)> {
    let mut order: Vec<usize> = (0..rest_x.len()).collect();
    order.sort_by(|&a, &b| rest_x[b].total_cmp(&rest_x[a]));
    let mut out: Vec<(Vec<usize>, f64)> = Vec::new();
    for j in order {
        match out.last_mut() {
            Some((w, x)) if (*x - rest_x[j]).abs() < 0.01 => {
                let n = w.len() as f64;
                *x = (*x * n + rest_x[j]) / (n + 1.0);
                w.push(j + 1);
            }
            _ => out.push((vec![j + 1], rest_x[j])),
        }
    }
    for (w, _) in &mut out {
        w.sort_unstable();
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rover driving at 0.05 m/s along a circle of radius 1 m (yaw rate
    /// 0.05 rad/s), with its rear axle 0.25 m behind G; `kick(t)` turns
    /// the body about G to the left, swinging the rear axle to the right.
    struct Tracked {
        t: Vec<f64>,
        yaw: Vec<f64>,
        path: Vec<[f64; 2]>,
        axles: Vec<Vec<[f64; 2]>>,
    }

    fn track(kick: impl Fn(f64) -> f64) -> Tracked {
        let t: Vec<f64> = (0..=400).map(|i| i as f64 * 0.1).collect();
        let mut yaw = Vec::new();
        let mut path = Vec::new();
        let mut rear = Vec::new();
        for &s in &t {
            let a = 0.05 * s;
            let g = [a.sin(), 1.0 - a.cos()];
            let psi = a + kick(s);
            let r = [g[0] - 0.25 * psi.cos(), g[1] - 0.25 * psi.sin()];
            yaw.push(psi);
            path.push(g);
            rear.push(r);
        }
        Tracked {
            t,
            yaw,
            path,
            axles: vec![rear],
        }
    }

    fn measure(kick: impl Fn(f64) -> f64) -> Slide {
        let r = track(kick);
        slide(
            &SlideTrack {
                times: &r.t,
                yaw: &r.yaw,
                path: &r.path,
                axles: &r.axles,
            },
            &[(vec![3, 4], -0.25)],
        )
        .expect("enough instants")
    }

    #[test]
    fn a_steady_turn_has_no_slide_and_its_rear_axle_swings_out_by_the_yaw_rate_only() {
        let s = measure(|_| 0.0);
        assert!((s.median_yaw_rate_deg_s - 0.05f64.to_degrees()).abs() < 1e-6);
        assert!(s.max_yaw_rate_excursion_deg_s < 1e-6, "{s:?}");
        assert!(s.max_yaw_change_deg < 1e-6);
        // The rear axle swings out by ψ̇·0.25 = 1.25 cm/s, not more.
        let a = &s.axles[0];
        assert!(
            (a.max_lateral_speed_m_s.abs() - 0.0125).abs() < 1e-4,
            "{a:?}"
        );
        assert_eq!(s.sudden, None);
    }

    #[test]
    fn a_sudden_sideways_slide_is_found_where_and_when_it_happens() {
        // At t = 25 s the rear swings right, the nose 10° left, over 0.5 s.
        let kick = |t: f64| (((t - 25.0) / 0.5).clamp(0.0, 1.0)) * 10f64.to_radians();
        let s = measure(kick);
        let slide = s.sudden.clone().expect("a slide");
        assert!((slide.t - 25.25).abs() <= 0.3, "{slide:?}");
        // G has travelled 0.05 m/s · 25 s.
        assert!((slide.distance_m - 1.26).abs() < 0.03, "{slide:?}");
        // Yaw to the left, rear axle to the right.
        assert!(slide.yaw_change_deg > SLIDE_YAW_DEG, "{slide:?}");
        assert!(slide.lateral_speed_m_s < -0.05, "{slide:?}");
        assert!((s.max_yaw_change_deg - 10.0).abs() < 0.1, "{s:?}");
        assert!((s.max_yaw_rate_excursion_deg_s - 20.0).abs() < 0.1, "{s:?}");
    }

    #[test]
    fn a_slow_drift_of_the_same_size_is_not_sudden() {
        // The same 10° spread over 20 s: at most 1° in any 2 s.
        let s = measure(|t: f64| ((t - 10.0) / 20.0).clamp(0.0, 1.0) * 10f64.to_radians());
        assert_eq!(s.sudden, None, "{s:?}");
        assert!(s.max_yaw_change_deg < SLIDE_YAW_DEG);
    }

    #[test]
    fn wheels_group_into_axles_by_rest_x_front_first() {
        let ax = axles_by_rest_x(&[0.33, 0.33, -0.03, -0.031, -0.3, -0.3]);
        assert_eq!(
            ax.iter().map(|a| a.0.clone()).collect::<Vec<_>>(),
            [vec![1, 2], vec![3, 4], vec![5, 6]]
        );
    }
}
