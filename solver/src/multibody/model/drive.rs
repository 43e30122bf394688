//! How the pair is driven: speed ramps, a fluctuating speed, and the drive
//! variants with their external torques.

/// A speed ramp: linear from `from` to `to` (rad/s) over `duration` (s), then constant.
#[derive(Debug, Clone, Copy)]
pub struct Ramp {
    pub from: f64,
    pub to: f64,
    pub duration: f64,
}

impl Ramp {
    /// (angle from t = 0, speed, acceleration) at time t.
    pub fn at(&self, t: f64) -> [f64; 3] {
        let acc = if self.duration > 0.0 {
            (self.to - self.from) / self.duration
        } else {
            0.0
        };
        if t <= self.duration {
            [self.from * t + 0.5 * acc * t * t, self.from + acc * t, acc]
        } else {
            let d = self.duration;
            let a0 = self.from * d + 0.5 * acc * d * d;
            [a0 + self.to * (t - d), self.to, 0.0]
        }
    }
}

/// A speed fluctuating about its mean: ω(t) = ω̄ (1 + a sin Ωt), as an
/// engine's speed ripple drives gear rattle.
#[derive(Debug, Clone, Copy)]
pub struct Fluctuation {
    /// Mean speed ω̄, rad/s; relative amplitude a; circular frequency Ω, rad/s.
    pub mean: f64,
    pub amplitude: f64,
    pub omega: f64,
}

impl Fluctuation {
    /// (angle from t = 0, speed, acceleration) at time t.
    pub fn at(&self, t: f64) -> [f64; 3] {
        let (w, a, o) = (self.mean, self.amplitude, self.omega);
        if o == 0.0 {
            return [w * t, w, 0.0];
        }
        let (s, c) = (o * t).sin_cos();
        [
            w * t + w * a * (1.0 - c) / o,
            w * (1.0 + a * s),
            w * a * o * c,
        ]
    }
}

/// How the pair is driven. Torques in N·m, positive in the drive sense.
#[derive(Debug, Clone, Copy)]
pub enum Drive {
    /// The wheel follows a speed ramp (the white paper's quasi-static 10 rpm
    /// run); the pinion carries the driving torque.
    WheelSpeed { speed: Ramp, pinion_torque: f64 },
    /// The pinion follows a speed ramp (the run-up); the wheel carries a
    /// resisting torque.
    PinionSpeed { speed: Ramp, wheel_torque: f64 },
    /// The pinion follows a fluctuating speed (rattle); the wheel carries a
    /// resisting (drag) torque.
    PinionFluctuating {
        speed: Fluctuation,
        wheel_torque: f64,
    },
    /// The pinion follows a speed ramp; the wheel's resisting torque rises
    /// from 0 to `wheel_torque` over `rise_s` by ADAMS's cubic STEP,
    /// STEP(t, 0, 0, rise_s, T) ([`crate::multibody::impact_law::step`]; constant for
    /// rise_s = 0): the drives of seeds 001 and 002.
    PinionSpeedLoadStep {
        speed: Ramp,
        wheel_torque: f64,
        rise_s: f64,
    },
    /// Both free: a driving pinion torque and a resisting wheel torque.
    Free {
        pinion_torque: f64,
        wheel_torque: f64,
    },
}

impl Drive {
    /// STEP(t, 0, 0, rise, T): T for rise ≤ 0.
    pub(super) fn load_step(torque: f64, rise: f64, t: f64) -> f64 {
        if rise > 0.0 {
            crate::multibody::impact_law::step(t, 0.0, 0.0, rise, torque)
        } else {
            torque
        }
    }

    /// Which coordinates are free.
    pub(crate) fn free(&self) -> [bool; 2] {
        match self {
            Drive::WheelSpeed { .. } => [true, false],
            Drive::PinionSpeed { .. }
            | Drive::PinionFluctuating { .. }
            | Drive::PinionSpeedLoadStep { .. } => [false, true],
            Drive::Free { .. } => [true, true],
        }
    }

    /// External generalized forces on (q₁, q₂) at time t.
    pub fn torques(&self, t: f64) -> [f64; 2] {
        match *self {
            Drive::PinionSpeedLoadStep {
                wheel_torque,
                rise_s,
                ..
            } => [0.0, -Self::load_step(wheel_torque, rise_s, t)],
            Drive::WheelSpeed { pinion_torque, .. } => [pinion_torque, 0.0],
            Drive::PinionSpeed { wheel_torque, .. }
            | Drive::PinionFluctuating { wheel_torque, .. } => [0.0, -wheel_torque],
            Drive::Free {
                pinion_torque,
                wheel_torque,
            } => [pinion_torque, -wheel_torque],
        }
    }
}
