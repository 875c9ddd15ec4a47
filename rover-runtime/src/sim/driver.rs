//! The one driver of a run's events: output instants, controller samples,
//! command breakpoints, sensor instants, and the checks after every
//! advance (a diverged integration, a roll-over). The whole run ([`run`](super::run())), the
//! step-wise run (`rover_scenario::Stepper`) and the live loop of
//! `rover drive` all advance through it, so the three take the same events
//! in the same order and stop for the same reasons.

use rover_dynamics::HeightField;
use rover_dynamics::plant::Plant;
use rover_integrate::Integrator;

use crate::control::Controller;

use super::error::{EMBEDDED_SINKAGE, EMBEDDED_SLIP, EMBEDDED_TIME, RunError};
use super::system::RoverSystem;

/// When a run's events fall, and when it has gone wrong.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RunOptions {
    /// End time \[s\]; `f64::INFINITY` for a run without an end (a
    /// step-wise or live run).
    pub duration: f64,
    /// Interval between output instants \[s\] (a live loop's step).
    pub output_step: f64,
    /// |φ| or |θ| beyond this is a roll-over \[rad\] (docs/MODEL.md §1: 80°).
    pub rollover_limit: f64,
}

/// The callback of a run without sensors.
fn no_sensors<P, H>(_t: f64, _y: &[f64], _sys: &mut RoverSystem<P, H>) -> Result<(), RunError> {
    Ok(())
}

/// Two event times within this fraction of (1 + t) are one instant: a
/// sample period and an output step that are multiples of each other
/// meet to rounding, and the integrator must not take a step of 1e-17 s
/// between them.
const SAME_INSTANT: f64 = 1e-12;

/// The schedule of one run: which output instant, controller sample and
/// command breakpoint come next. It holds no state of the rover; the
/// caller keeps `(t, y)`, the system and the integrator, and passes them
/// to each call.
#[derive(Clone, Debug)]
pub struct Driver {
    opts: RunOptions,
    /// The controller's sample period (active suspension, waypoint legs).
    sample: Option<f64>,
    /// The sensors' period ([`Driver::with_sensor_period`]).
    sensor: Option<f64>,
    /// Times at which the commands jump, ascending, in (0, duration].
    breaks: Vec<f64>,
    /// The next output instant is `k_out · output_step`.
    k_out: u64,
    /// The next controller sample is at `k_sample · sample`.
    k_sample: u64,
    /// The next sensor instant is at `k_sensor · sensor`.
    k_sensor: u64,
    /// The first breakpoint not yet passed.
    next_break: usize,
    /// On a soil, since when every wheel on the ground has slipped above
    /// [`EMBEDDED_SLIP`].
    slipping_since: Option<f64>,
    /// The end of settling: a rover landing on its wheels is not embedded.
    settle: f64,
    /// An instant no step reaches past while it is ahead
    /// ([`Driver::with_landing`]).
    landing: f64,
}

impl Driver {
    /// The schedule of a run with `control` (its sample period and
    /// breakpoints), at t = 0 before any event.
    pub fn new(control: &Controller, opts: RunOptions) -> Self {
        let mut breaks: Vec<f64> = control
            .breakpoints()
            .into_iter()
            // One at the end too: the last step must not see the commands
            // switch on at its end (a run that ends as settling does).
            .filter(|&b| b > 0.0 && b <= opts.duration)
            .collect();
        breaks.sort_by(f64::total_cmp);
        Self {
            opts,
            sample: control.sample_period(),
            sensor: None,
            breaks,
            k_out: 0,
            k_sample: 0,
            k_sensor: 0,
            next_break: 0,
            slipping_since: None,
            settle: control.settle_time(),
            landing: f64::INFINITY,
        }
    }

    /// The schedule with the integrator landing on `at` (no step passes it
    /// while it is ahead; an output instant within rounding of it is it)
    /// though the run goes on: a stepped run with no end of its own lands
    /// on its scenario's end as the whole run does, and so takes the whole
    /// run's steps and times up to it.
    pub fn with_landing(mut self, at: f64) -> Self {
        self.landing = at;
        self
    }

    /// The schedule with sensor instants every `period` seconds from t = 0
    /// (`None`, or a period that is not finite and positive: none). The
    /// integrator lands on each, as on an output instant, and goes on
    /// without a restart: nothing jumps there. [`Driver::start_with`] and
    /// [`Driver::advance_with`] call their callback at each;
    /// [`Driver::start`] and [`Driver::advance`] land on them all the same,
    /// so that a run stepped without the callback takes the steps of the
    /// run with it.
    pub fn with_sensor_period(mut self, period: Option<f64>) -> Self {
        self.sensor = period.filter(|p| p.is_finite() && *p > 0.0);
        self
    }

    /// The sensors' period, if the schedule has sensor instants.
    pub fn sensor_period(&self) -> Option<f64> {
        self.sensor
    }

    /// The options the schedule was made with.
    pub fn options(&self) -> &RunOptions {
        &self.opts
    }

    /// Back to t = 0, before any event (the caller puts the state, the
    /// system and the integrator back).
    pub fn rewind(&mut self) {
        self.k_out = 0;
        self.k_sample = 0;
        self.k_sensor = 0;
        self.next_break = 0;
        self.slipping_since = None;
    }

    /// Whether `t` is the run's end.
    pub fn finished(&self, t: f64) -> bool {
        t >= self.opts.duration
    }

    /// The events of t = 0: the controller's first sample; t = 0 is the
    /// first output instant (and sensor instant). Call once, after
    /// [`Driver::new`] or [`Driver::rewind`].
    pub fn start<P: Plant, H: HeightField, I: Integrator>(
        &mut self,
        sys: &mut RoverSystem<P, H>,
        integ: &mut I,
        t: f64,
        y: &[f64],
    ) {
        // The callback does nothing, so nothing fails.
        let _ = self.start_with(sys, integ, t, y, &mut no_sensors);
    }

    /// [`Driver::start`], calling `on_sensor(t, y, sys)` at t = 0 when the
    /// schedule has sensor instants (after the controller's sample). Its
    /// error is returned as it is.
    pub fn start_with<P: Plant, H: HeightField, I: Integrator, F>(
        &mut self,
        sys: &mut RoverSystem<P, H>,
        integ: &mut I,
        t: f64,
        y: &[f64],
        on_sensor: &mut F,
    ) -> Result<(), RunError>
    where
        F: FnMut(f64, &[f64], &mut RoverSystem<P, H>) -> Result<(), RunError>,
    {
        self.sample_due(sys, integ, t, y);
        self.k_out = 1;
        self.sensor_due(sys, t, y, on_sensor)
    }

    /// Advance `(t, y)` to the next output instant, or to the run's end
    /// when that comes first (the end is always an output instant, whether
    /// the output step divides the duration or not), through every
    /// controller sample, command breakpoint and sensor instant before it.
    /// The integrator restarts after a breakpoint (the commands jump) and
    /// after a sample that changed something; the samples due at the
    /// instant reached are taken before this returns. After each advance
    /// the attitude is checked: past half a turn is a diverged integration,
    /// past the limit a roll-over.
    ///
    /// On failure, `(t, y)` are those of the last step the integrator
    /// accepted (for a roll-over, the event at which it was seen), and the
    /// error names the time. Allocates nothing.
    pub fn advance<P: Plant, H: HeightField, I: Integrator>(
        &mut self,
        sys: &mut RoverSystem<P, H>,
        integ: &mut I,
        t: &mut f64,
        y: &mut [f64],
    ) -> Result<(), RunError> {
        self.advance_with(sys, integ, t, y, &mut no_sensors)
    }

    /// [`Driver::advance`], calling `on_sensor(t, y, sys)` at each sensor
    /// instant reached ([`Driver::with_sensor_period`]), after the checks
    /// and the controller's sample there; the callback may evaluate the
    /// system (`RoverSystem::evaluate_at`) to read its accelerations and
    /// commands. The integrator is not restarted: a callback that changes
    /// the commands should restart it itself. Its error ends the advance
    /// there. Allocates nothing but what the callback does.
    pub fn advance_with<P: Plant, H: HeightField, I: Integrator, F>(
        &mut self,
        sys: &mut RoverSystem<P, H>,
        integ: &mut I,
        t: &mut f64,
        y: &mut [f64],
        on_sensor: &mut F,
    ) -> Result<(), RunError>
    where
        F: FnMut(f64, &[f64], &mut RoverSystem<P, H>) -> Result<(), RunError>,
    {
        self.advance_until(sys, integ, t, y, f64::INFINITY, on_sensor)
            .map(|_| ())
    }

    /// The next output instant \[s\].
    pub fn next_output(&self) -> f64 {
        (self.k_out as f64 * self.opts.output_step).min(self.opts.duration)
    }

    /// [`Driver::advance_with`], stopping at `until` when it comes before
    /// the next output instant: a communication point of a co-simulation
    /// master (an FMU's step) that is no output instant. The integrator
    /// lands there as on any event, without a restart; the next call goes
    /// on to the output instant. Returns whether an output instant was
    /// reached. With `until` on the output instants, the steps are those of
    /// [`Driver::advance`]. Allocates nothing but what the callback does.
    pub fn advance_until<P: Plant, H: HeightField, I: Integrator, F>(
        &mut self,
        sys: &mut RoverSystem<P, H>,
        integ: &mut I,
        t: &mut f64,
        y: &mut [f64],
        until: f64,
        on_sensor: &mut F,
    ) -> Result<bool, RunError>
    where
        F: FnMut(f64, &[f64], &mut RoverSystem<P, H>) -> Result<(), RunError>,
    {
        loop {
            let t_out = self.k_out as f64 * self.opts.output_step;
            while self.next_break < self.breaks.len() && self.breaks[self.next_break] <= *t {
                self.next_break += 1;
            }
            let mut target = t_out.min(self.opts.duration);
            if self.landing > *t {
                target = target.min(self.landing);
            }
            // A stop within rounding of the output instant is the instant.
            let stop = (until < target - SAME_INSTANT * (1.0 + target)).then_some(until);
            if let Some(u) = stop {
                target = u;
            }
            if let Some(dt) = self.sample {
                target = target.min(self.k_sample as f64 * dt);
            }
            if let Some(dt) = self.sensor {
                target = target.min(self.k_sensor as f64 * dt);
            }
            // A breakpoint on (or within rounding of) the next event is
            // one too: the integrator must restart there, not carry its
            // history across the jump (BDF's step control stalls right
            // before a jump it steps over).
            let at_break = self.next_break < self.breaks.len()
                && self.breaks[self.next_break] <= target + SAME_INSTANT * (1.0 + target);
            if at_break {
                target = self.breaks[self.next_break];
            }
            sys.set_next_break(at_break.then_some(target));
            // An output instant that is no other event changes nothing: the
            // integrator may step past it, up to the next event, and give
            // the state there from its interpolant.
            let limit = self.next_event(until, target);
            let advanced = if limit > target + SAME_INSTANT * (1.0 + target) {
                integ.advance_output(sys, t, y, target, limit)
            } else {
                integ.advance(sys, t, y, target)
            };
            sys.set_next_break(None);
            if let Err(e) = advanced {
                let at = e.time().unwrap_or(*t);
                return Err(RunError::Integration {
                    t: at,
                    message: e.to_string(),
                    step_control: e.is_step_control(),
                });
            }
            if at_break {
                integ.restart();
            }
            self.check_attitude(*t, y)?;
            self.check_soil(sys, *t, y)?;
            self.sample_due(sys, integ, *t, y);
            self.sensor_due(sys, *t, y, on_sensor)?;
            if (t_out - *t).abs() <= SAME_INSTANT * (1.0 + *t) || self.finished(*t) {
                self.k_out += 1;
                return Ok(true);
            }
            if stop.is_some_and(|u| (u - *t).abs() <= SAME_INSTANT * (1.0 + *t)) {
                return Ok(false);
            }
        }
    }

    /// The first instant after `target` at which the run may change the
    /// system or restart the integrator: the next breakpoint, controller
    /// sample or sensor instant, the stop `until`, the landing instant, or
    /// the run's end; for
    /// [`Integrator::advance_output`].
    fn next_event(&self, until: f64, target: f64) -> f64 {
        let mut limit = self.opts.duration.min(until);
        if self.landing >= target {
            limit = limit.min(self.landing);
        }
        if let Some(&b) = self.breaks.get(self.next_break) {
            limit = limit.min(b);
        }
        if let Some(dt) = self.sample {
            limit = limit.min(self.k_sample as f64 * dt);
        }
        if let Some(dt) = self.sensor {
            limit = limit.min(self.k_sensor as f64 * dt);
        }
        limit.max(target)
    }

    /// The sensors' callback, when a sensor instant is due at `t`.
    fn sensor_due<P: Plant, H: HeightField, F>(
        &mut self,
        sys: &mut RoverSystem<P, H>,
        t: f64,
        y: &[f64],
        on_sensor: &mut F,
    ) -> Result<(), RunError>
    where
        F: FnMut(f64, &[f64], &mut RoverSystem<P, H>) -> Result<(), RunError>,
    {
        let Some(dt) = self.sensor else {
            return Ok(());
        };
        if (self.k_sensor as f64 * dt - t).abs() > SAME_INSTANT * (1.0 + t) {
            return Ok(());
        }
        self.k_sensor += 1;
        on_sensor(t, y, sys)
    }

    /// The controller's sample, when one is due at `t`.
    fn sample_due<P: Plant, H: HeightField, I: Integrator>(
        &mut self,
        sys: &mut RoverSystem<P, H>,
        integ: &mut I,
        t: f64,
        y: &[f64],
    ) {
        let Some(dt) = self.sample else { return };
        if (self.k_sample as f64 * dt - t).abs() > SAME_INSTANT * (1.0 + t) {
            return;
        }
        let n = sys.dof();
        let (x, rest) = y.split_at(n);
        if sys.control.sample(t, x, &rest[..n], &mut sys.plant) {
            integ.restart();
        }
        self.k_sample += 1;
    }

    /// On a soil, a rover that cannot advance, from the contact reports of
    /// the last evaluation (at or just before `t`): every wheel on the
    /// ground slipping above [`EMBEDDED_SLIP`] for [`EMBEDDED_TIME`], or a
    /// wheel sunk past [`EMBEDDED_SINKAGE`] of its radius. Judged after
    /// settling: a rover landing on soft ground sinks deeper for a moment.
    fn check_soil<P: Plant, H: HeightField>(
        &mut self,
        sys: &RoverSystem<P, H>,
        t: f64,
        y: &[f64],
    ) -> Result<(), RunError> {
        let Some(ground) = sys.ground.as_ref().filter(|g| g.soil().is_some()) else {
            return Ok(());
        };
        if t < self.settle {
            return Ok(());
        }
        let embedded = |why: String| RunError::Embedded {
            t,
            x: y[0],
            y: y[1],
            why,
        };
        let reports = sys.reports();
        let radii = ground.radii();
        let sunk = || {
            reports
                .iter()
                .zip(radii)
                .enumerate()
                .filter(|(_, (r, radius))| r.sinkage > EMBEDDED_SINKAGE * **radius)
        };
        if sunk().next().is_some() {
            let wheels: Vec<String> = sunk()
                .map(|(j, (r, radius))| {
                    format!(
                        "wheel {} sank {:.3} m, past half its radius ({radius} m)",
                        j + 1,
                        r.sinkage
                    )
                })
                .collect();
            return Err(embedded(wheels.join("; ")));
        }
        let on_ground = || reports.iter().filter(|r| r.patches > 0);
        let all_slipping = on_ground().count() > 0 && on_ground().all(|r| r.slip > EMBEDDED_SLIP);
        if !all_slipping {
            self.slipping_since = None;
            return Ok(());
        }
        let since = *self.slipping_since.get_or_insert(t);
        if t - since < EMBEDDED_TIME {
            return Ok(());
        }
        let wheels: Vec<String> = reports
            .iter()
            .enumerate()
            .filter(|(_, r)| r.patches > 0)
            .map(|(j, r)| format!("wheel {} {:.3}", j + 1, r.slip))
            .collect();
        Err(embedded(format!(
            "every wheel on the ground has slipped above {EMBEDDED_SLIP} since t = {since:.3} s (slip now: {})",
            wheels.join(", ")
        )))
    }

    /// A diverged integration or a roll-over, from the attitude at `t`.
    fn check_attitude(&self, t: f64, y: &[f64]) -> Result<(), RunError> {
        let (roll, pitch) = (y[3], y[4]);
        // Past half a turn between two events is no roll-over but a
        // numerical blow-up: a rover tips through the limit first.
        if roll.abs() > std::f64::consts::PI || pitch.abs() > std::f64::consts::PI {
            return Err(RunError::Diverged {
                t,
                roll_deg: roll.to_degrees(),
                pitch_deg: pitch.to_degrees(),
            });
        }
        let limit = self.opts.rollover_limit;
        if roll.abs() > limit || pitch.abs() > limit {
            return Err(RunError::RolledOver {
                t,
                roll_deg: roll.to_degrees(),
                pitch_deg: pitch.to_degrees(),
                limit_deg: limit.to_degrees(),
            });
        }
        Ok(())
    }
}
