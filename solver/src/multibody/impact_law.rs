//! The impact-function contact law of general-purpose multibody codes
//! (ADAMS `IMPACT`, NX Motion 3D contact), as seeds 001 and 002 use it for
//! spiral bevel gears, and the Hertz stiffness they give it.
//!
//! In terms of the penetration δ = s₀ − s ≥ 0 (s the distance, s₀ the
//! distance at first contact) and its rate δ̇ = −ṡ, SI units throughout:
//!
//!   F(δ, δ̇) = max(0, K δ^e + C δ̇ STEP(δ, 0, 0, d, 1))   for δ > 0, else 0,
//!
//! which is ADAMS's `max(0, K (s₀ − s)^e − C ṡ STEP(s, s₀ − d, 1, s₀, 0))`
//! written in δ (the cubic STEP is symmetric: STEP(s, s₀ − d, 1, s₀, 0) =
//! STEP(δ, 0, 0, d, 1)). K (N/m^e), exponent e, damping C (N·s/m) reached
//! fully at the penetration depth d (m). The seeds state K, C and d in
//! mm-based units; [`ImpactLaw::from_mm_units`] converts them
//! (K_SI = K_mm · 1000^e, C_SI = 1000 C_mm, d_SI = d_mm / 1000).

use formats::summaries::ImpactLawSummary;
use geometry::scene::{ImpactSettings, StepShape};

/// ADAMS's cubic STEP(x, x₀, h₀, x₁, h₁): h₀ for x ≤ x₀, h₁ for x ≥ x₁,
/// between them h₀ + (h₁ − h₀) Δ² (3 − 2Δ) with Δ = (x − x₀)/(x₁ − x₀).
/// Value and first derivative are continuous (C¹); the derivative is zero
/// at both ends, the second derivative jumps there from 0 to
/// ±6 (h₁ − h₀)/(x₁ − x₀)². Needs x₁ > x₀.
pub fn step(x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> f64 {
    step_with_slope(x, x0, h0, x1, h1).0
}

/// STEP and its first derivative in x: dSTEP/dx = (h₁ − h₀) 6 Δ (1 − Δ) / (x₁ − x₀)
/// between the ends, zero outside.
pub fn step_with_slope(x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> (f64, f64) {
    if x <= x0 {
        return (h0, 0.0);
    }
    if x >= x1 {
        return (h1, 0.0);
    }
    let w = x1 - x0;
    let d = (x - x0) / w;
    (
        h0 + (h1 - h0) * d * d * (3.0 - 2.0 * d),
        (h1 - h0) * 6.0 * d * (1.0 - d) / w,
    )
}

/// The haversine step: h₀ for x ≤ x₀, h₁ for x ≥ x₁, between them
/// h₀ + (h₁ − h₀) (1 − cos πΔ)/2, Δ = (x − x₀)/(x₁ − x₀), and its slope
/// (h₁ − h₀) π sin(πΔ) / (2 (x₁ − x₀)). Like the cubic STEP it is C¹ with
/// zero slope at both ends; its largest slope is π/2 (h₁ − h₀)/(x₁ − x₀)
/// against the cubic's 3/2 times that, and it lies below the cubic on the
/// first half of the ramp (above on the second).
pub fn haversine_with_slope(x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> (f64, f64) {
    if x <= x0 {
        return (h0, 0.0);
    }
    if x >= x1 {
        return (h1, 0.0);
    }
    let w = x1 - x0;
    let a = std::f64::consts::PI * (x - x0) / w;
    (
        h0 + (h1 - h0) * 0.5 * (1.0 - a.cos()),
        (h1 - h0) * std::f64::consts::PI * a.sin() / (2.0 * w),
    )
}

/// The impact law's parameters, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactLaw {
    /// K, N/m^e.
    pub stiffness: f64,
    /// e (force exponent; 1.5 is Hertz's point contact).
    pub exponent: f64,
    /// C, N·s/m.
    pub damping: f64,
    /// d, m: the penetration over which the damping ramps in.
    pub depth: f64,
    /// Shape of that ramp.
    pub step: StepShape,
}

/// Force of the law and its tangents.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ImpactForce {
    /// F, N (≥ 0).
    pub force: f64,
    /// ∂F/∂δ, N/m, and ∂F/∂δ̇, N·s/m (zero where F is clamped at zero).
    pub d_penetration: f64,
    pub d_rate: f64,
}

impl ImpactLaw {
    /// From the seeds' mm-based units: K in N/mm^e, C in N·s/mm, d in mm.
    pub fn from_mm_units(
        stiffness_n_per_mm_e: f64,
        exponent: f64,
        damping_n_s_per_mm: f64,
        depth_mm: f64,
    ) -> Self {
        ImpactLaw {
            stiffness: stiffness_n_per_mm_e * 1000f64.powf(exponent),
            exponent,
            damping: damping_n_s_per_mm * 1e3,
            depth: depth_mm * 1e-3,
            step: StepShape::Cubic,
        }
    }

    /// Stiffness term K δ^e (N) and its derivative K e δ^(e−1) (N/m); zero for δ ≤ 0.
    pub fn elastic(&self, delta: f64) -> (f64, f64) {
        if delta <= 0.0 {
            return (0.0, 0.0);
        }
        let p = self.stiffness * delta.powf(self.exponent - 1.0);
        (p * delta, self.exponent * p)
    }

    /// Potential of the stiffness term, ∫₀^δ K x^e dx = K δ^(e+1)/(e + 1), J.
    pub fn potential(&self, delta: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        self.stiffness * delta.powf(self.exponent + 1.0) / (self.exponent + 1.0)
    }

    /// Damping weight STEP(δ, 0, 0, d, 1) and its derivative in δ (1/m),
    /// of the law's step shape.
    pub fn damping_weight(&self, delta: f64) -> (f64, f64) {
        match self.step {
            StepShape::Cubic => step_with_slope(delta, 0.0, 0.0, self.depth, 1.0),
            StepShape::Haversine => haversine_with_slope(delta, 0.0, 0.0, self.depth, 1.0),
        }
    }

    /// F(δ, δ̇) = max(0, K δ^e + C δ̇ STEP(δ, 0, 0, d, 1)) for δ > 0, and
    /// its tangents ∂F/∂δ = K e δ^(e−1) + C δ̇ STEP′(δ), ∂F/∂δ̇ = C STEP(δ)
    /// where F > 0 (zero where the clamp holds).
    pub fn force(&self, delta: f64, rate: f64) -> ImpactForce {
        if delta <= 0.0 {
            return ImpactForce::default();
        }
        let (fe, ke) = self.elastic(delta);
        let (w, dw) = self.damping_weight(delta);
        let f = fe + self.damping * rate * w;
        if f <= 0.0 {
            return ImpactForce::default();
        }
        ImpactForce {
            force: f,
            d_penetration: ke + self.damping * rate * dw,
            d_rate: self.damping * w,
        }
    }
}

/// Coulomb friction with a speed-dependent coefficient, as ADAMS's contact
/// friction: for slip speed v = |v_slip|,
///
///   μ(v) = STEP(v, 0, 0, v_s, μ_s)            for v ≤ v_s,
///   μ(v) = STEP(v, v_s, μ_s, v_d, μ_d)        for v_s < v < v_d,
///   μ(v) = μ_d                                for v ≥ v_d,
///
/// μ_s the static and μ_d the dynamic coefficient, v_s the stiction
/// transition speed and v_d the friction transition speed (m/s; ADAMS's
/// defaults are 0.1 and 1 m/s, which the seeds leave unstated). The force
/// opposes the slip: F_t = −μ(|v|) sgn(v) F_n. μ is C¹ in v and zero at
/// zero slip (no true stiction).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Friction {
    pub static_coefficient: f64,
    pub dynamic_coefficient: f64,
    /// v_s and v_d, m/s (0 < v_s < v_d).
    pub stiction_speed: f64,
    pub transition_speed: f64,
}

impl Friction {
    /// μ(v) and dμ/dv (s/m) at slip speed v ≥ 0 (|v| is taken).
    pub fn coefficient(&self, v: f64) -> (f64, f64) {
        let v = v.abs();
        if v <= self.stiction_speed {
            step_with_slope(v, 0.0, 0.0, self.stiction_speed, self.static_coefficient)
        } else {
            step_with_slope(
                v,
                self.stiction_speed,
                self.static_coefficient,
                self.transition_speed,
                self.dynamic_coefficient,
            )
        }
    }
}

/// Effective modulus E* from 1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂ (units of E).
pub fn effective_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    1.0 / ((1.0 - nu1 * nu1) / e1 + (1.0 - nu2 * nu2) / e2)
}

/// Effective radius R from 1/R = 1/R₁ + 1/R₂ (units of R).
pub fn effective_radius(r1: f64, r2: f64) -> f64 {
    r1 * r2 / (r1 + r2)
}

/// Hertz point-contact stiffness K = 4/3 √R E* (F = K δ^1.5). In SI (R in
/// m, E* in Pa) K is in N/m^1.5; with R in mm and E* in N/mm² in N/mm^1.5.
pub fn hertz_point_stiffness(radius: f64, modulus: f64) -> f64 {
    4.0 / 3.0 * radius.sqrt() * modulus
}

/// Γ(x) for x > 0 (Lanczos, g = 7, 9 terms; relative error ≈ 1e-15).
pub fn gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        return std::f64::consts::PI / ((std::f64::consts::PI * x).sin() * gamma(1.0 - x));
    }
    let x = x - 1.0;
    let mut a = C[0];
    for (k, c) in C.iter().enumerate().skip(1) {
        a += c / (x + k as f64);
    }
    let t = x + G + 0.5;
    (2.0 * std::f64::consts::PI).sqrt() * t.powf(x + 0.5) * (-t).exp() * a
}

/// Closed form of one undamped, frictionless impact under F = K δ^e of two
/// bodies of effective mass m (kg) approaching at v₀ (m/s) (Johnson,
/// Contact Mechanics, §11.4, there for e = 3/2): energy ½ m v₀² = K δ_m^(e+1)
/// /(e + 1) gives the largest penetration δ_m and the peak force K δ_m^e;
/// the contact lasts
///
///   t_c = 2 (δ_m / v₀) ∫₀¹ dx / √(1 − x^(e+1)) = 2 (δ_m / v₀) B(1/(e+1), ½)/(e + 1),
///
/// B the beta function (for e = 3/2: t_c = 2.9432 δ_m / v₀).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SingleImpact {
    pub max_penetration: f64,
    pub peak_force: f64,
    pub contact_time: f64,
}

/// [`SingleImpact`] of the stiffness term of `law` (damping ignored).
pub fn single_impact(law: &ImpactLaw, mass: f64, speed: f64) -> SingleImpact {
    let e = law.exponent;
    let dm = ((e + 1.0) * 0.5 * mass * speed * speed / law.stiffness).powf(1.0 / (e + 1.0));
    let a = 1.0 / (e + 1.0);
    let beta = gamma(a) * gamma(0.5) / gamma(a + 0.5);
    SingleImpact {
        max_penetration: dm,
        peak_force: law.stiffness * dm.powf(e),
        contact_time: 2.0 * dm / speed * beta * a,
    }
}

/// First-order estimate of the coefficient of restitution that the damping
/// gives in a single impact (small C): the energy the damping dissipates
/// along the undamped history, ΔE = ∮ C STEP(δ) δ̇ dδ = 2 C v₀ ∫₀^δm
/// STEP(δ) √(1 − (δ/δ_m)^(e+1)) dδ (approach and rebound alike to first
/// order), and ε = √(1 − ΔE / (½ m v₀²)). For d ≪ δ_m this is ε ≈ 1 −
/// 2 C δ_m I_e/(m v₀) with I_e = ∫₀¹ √(1 − x^(e+1)) dx, the linear
/// decrease in C that Hunt & Crossley (1975) derive for a damping
/// proportional to δ^e. Approximate: the damped history is slower on the
/// way in and faster on the way out, so the estimate holds to O(C²).
/// Returns 0 when the estimate dissipates all the energy.
pub fn restitution_estimate(law: &ImpactLaw, mass: f64, speed: f64) -> f64 {
    let dm = single_impact(law, mass, speed).max_penetration;
    let e1 = law.exponent + 1.0;
    // Composite Simpson in x = δ/δ_m; the square-root end is resolved by
    // substituting x = 1 − y² (dx = 2y dy).
    let n = 2000;
    let f = |y: f64| {
        let x: f64 = 1.0 - y * y;
        let w = law.damping_weight(x * dm).0;
        w * (1.0 - x.powf(e1)).max(0.0).sqrt() * 2.0 * y
    };
    let h = 1.0 / n as f64;
    let mut s = f(0.0) + f(1.0);
    for k in 1..n {
        s += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k as f64 * h);
    }
    let integral = s * h / 3.0 * dm;
    let loss = 2.0 * law.damping * speed * integral;
    (1.0 - loss / (0.5 * mass * speed * speed)).max(0.0).sqrt()
}

/// A seed's Hertz stiffness recomputed from its own inputs (mm and N/mm²,
/// the seeds' units; K in N/mm^1.5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SeedStiffness {
    /// R₁, R₂ and R, mm.
    pub radii_mm: [f64; 2],
    pub radius_mm: f64,
    /// E* from E and ν, N/mm².
    pub modulus_n_per_mm2: f64,
    /// 4/3 √R E*, N/mm^1.5, and the value the seed prints.
    pub recomputed: f64,
    pub printed: f64,
}

impl SeedStiffness {
    /// Recomputes 4/3 √R E* with R from (R₁, R₂) and E* from two equal
    /// materials (E, ν), against the printed value.
    pub fn new(radii_mm: [f64; 2], e: f64, nu: f64, printed: f64) -> Self {
        let r = effective_radius(radii_mm[0], radii_mm[1]);
        let m = effective_modulus(e, nu, e, nu);
        SeedStiffness {
            radii_mm,
            radius_mm: r,
            modulus_n_per_mm2: m,
            recomputed: hertz_point_stiffness(r, m),
            printed,
        }
    }

    /// printed / recomputed.
    pub fn ratio(&self) -> f64 {
        self.printed / self.recomputed
    }
}

/// Seed 001 (9/40, ADAMS): both members 20CrMnTi, E = 2.07e5 N/mm²,
/// ν = 0.25; R₁, R₂ the end-module pitch radii m z/2 = 40.5 and 180 mm,
/// R = 33.061 mm as printed (the seed labels it N/mm²). E* = 1.104e5
/// N/mm² (printed rounded to 1.1e5) and K = 4/3 √R E* = 8.464e5 N/mm^1.5;
/// the printed 8.433e5 reproduces only with the rounded E* = 1.1e5
/// (−0.37 %). The seed then uses this K, derived for F = K δ^1.5, with the
/// exponent j = 2.2: with δ in mm, K δ^2.2 is a different law (weaker below
/// 1 mm penetration), and the K of the printed units (N/mm²) belongs to
/// neither.
pub fn seed_001_stiffness() -> SeedStiffness {
    SeedStiffness::new([40.5, 180.0], 2.07e5, 0.25, 8.433e5)
}

/// Seed 002 (9/37, NX): C45, E = 2.07e5 N/mm², ν = 0.285, its Eq. (9) with
/// α = 1 and R₁, R₂ "the exterior transverse pitch circle radii". With the
/// pitch radii of its Table 1 (d = 40.5 and 166.5 mm: 20.25 and 83.25 mm)
/// K = 6.062e5 N/mm^1.5; with the back-cone (Tredgold) radii of the outer
/// transverse section, r/cos δ = 20.84 and 352.3 mm
/// ([`seed_002_back_cone_stiffness`]), K = 6.66e5 N/mm^1.5. The printed
/// k = 6.65e7 (no unit) is 100 times the back-cone value (110 times the
/// pitch-radius value): no choice of R with α ≤ 1 and E in N/mm²
/// reproduces it; E in N/cm² (2.07e7) and R in mm would.
pub fn seed_002_stiffness() -> SeedStiffness {
    SeedStiffness::new([20.25, 83.25], 2.07e5, 0.285, 6.65e7)
}

/// Seed 002's K with the back-cone radii r/cos δ (pitch angles 13.671° and
/// 76.329° of its Table 1), see [`seed_002_stiffness`].
pub fn seed_002_back_cone_stiffness() -> SeedStiffness {
    let r1 = 20.25 / 13.671f64.to_radians().cos();
    let r2 = 83.25 / 76.329f64.to_radians().cos();
    SeedStiffness::new([r1, r2], 2.07e5, 0.285, 6.65e7)
}

/// The impact law of the scene's settings in SI ([`ImpactLaw`]), its
/// friction (None when both coefficients are zero), and its summary: K
/// from the scene, or the Hertz point-contact K = 4/3 √R E* with R from
/// the outer pitch radii R_e sin δ and E* from both members' materials,
/// as the seeds compute it.
pub fn from_settings(
    pair: &geometry::design::PairData,
    s: &ImpactSettings,
) -> (ImpactLaw, Option<Friction>, ImpactLawSummary) {
    let radii =
        [0, 1].map(|i| pair.outer_cone_distance() * pair.members[i].pitch_angle.sin() * 1e3);
    let [p, w] = &pair.members;
    let modulus = effective_modulus(
        p.youngs_modulus * 1e-6,
        p.poisson_ratio,
        w.youngs_modulus * 1e-6,
        w.poisson_ratio,
    );
    let hertz = hertz_point_stiffness(effective_radius(radii[0], radii[1]), modulus);
    let (k, source) = match s.stiffness_n_per_mm_e {
        Some(k) => (k, "scene"),
        None => (hertz, "hertz"),
    };
    let law = ImpactLaw {
        step: s.damping_step,
        ..ImpactLaw::from_mm_units(k, s.exponent, s.damping_n_s_per_mm, s.penetration_depth_mm)
    };
    let friction = (s.static_friction > 0.0 || s.dynamic_friction > 0.0).then_some(Friction {
        static_coefficient: s.static_friction,
        dynamic_coefficient: s.dynamic_friction,
        stiction_speed: s.stiction_speed_mm_s * 1e-3,
        transition_speed: s.friction_transition_speed_mm_s * 1e-3,
    });
    let summary = ImpactLawSummary {
        stiffness_n_per_mm_e: k,
        stiffness_source: source.into(),
        hertz_stiffness_n_per_mm_1_5: hertz,
        hertz_radii_mm: radii,
        exponent: s.exponent,
        damping_n_s_per_mm: s.damping_n_s_per_mm,
        penetration_depth_mm: s.penetration_depth_mm,
        static_friction: s.static_friction,
        dynamic_friction: s.dynamic_friction,
        stiction_speed_mm_s: s.stiction_speed_mm_s,
        friction_transition_speed_mm_s: s.friction_transition_speed_mm_s,
        damping_step: s.damping_step.name().into(),
    };
    (law, friction, summary)
}
