//! The seed pairs' design files in `reference/` keep the values their
//! papers publish (teeth, angles, module, cone distances, material).
//!
//! Run with `cargo test --release -p preprocess --test seed_published_data -- --nocapture`
//! to see every value against the paper's.

use geometry::design::{Hand, Member, PairData};
use geometry::design_file::load_pair;
use std::path::Path;

const REFERENCE: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../reference");

/// Which module a paper gives.
#[derive(Clone, Copy)]
enum Module {
    /// Outer (heel) transverse module, "end module", mm.
    OuterTransverse(f64),
    /// Mean normal module with the mean cone distance, mm.
    MeanNormal {
        module: f64,
        mean_cone_distance: f64,
    },
}

/// Values as printed in a seed paper.
struct Published {
    file: &'static str,
    teeth: [u32; 2],
    hands: Option<[Hand; 2]>,
    module: Module,
    /// Face width, when printed (else the file's chosen value is used in the conversions).
    face_width_mm: Option<f64>,
    spiral_angle_deg: f64,
    /// Pressure angle, when printed (used on both flanks).
    pressure_angle_deg: Option<f64>,
    shaft_angle_deg: f64,
    /// Printed pitch angles and the tolerance their printing allows.
    pitch_angles_deg: Option<([f64; 2], f64)>,
    /// Printed pitch diameters (module × teeth), mm.
    pitch_diameters_mm: Option<[f64; 2]>,
    /// Printed Young's modulus (GPa) and Poisson ratio.
    material: Option<(f64, f64)>,
}

fn published() -> Vec<Published> {
    use Hand::{Left, Right};
    vec![
        // Seed 000 (shared/seeds/000_93b78a1691de234a.txt), Table 1 "Gear blank geometry
        // data and material": 20/43, RH/LH, mean spiral 32.000 deg, mean normal module
        // 4.325 mm, mean cone distance 120.940 mm, face width 41.000 mm, pitch angles
        // 24.944/65.056 deg, "Steel". No pressure angle, shaft angle or E/nu printed
        // (shaft angle 90 deg from the pitch angles' sum).
        Published {
            file: "white_paper_20x43.toml",
            teeth: [20, 43],
            hands: Some([Right, Left]),
            module: Module::MeanNormal {
                module: 4.325,
                mean_cone_distance: 120.940,
            },
            face_width_mm: Some(41.0),
            spiral_angle_deg: 32.0,
            pressure_angle_deg: None,
            shaft_angle_deg: 90.0,
            pitch_angles_deg: Some(([24.944, 65.056], 0.001)),
            pitch_diameters_mm: None,
            material: None,
        },
        // Seed 001 (shared/seeds/001_c43e8a84d769cf72.txt), Table 1 "The Proper Geometric
        // Parameters Of Spiral Bevel Gears": 9/40, end module 9 mm, pressure angle 20 deg,
        // helix angle 35 deg, shaft angle 90 deg, breadth 60 mm (pinion) / 54 mm (wheel,
        // the common face width), nodal bevel (pitch) angles 13/77 deg, printed to the
        // degree (9/40 gives 12.680/77.320). The printed cone distance 180 mm follows from
        // the rounded 13 deg and is not checked. Section 3.2: E = 2.07e5 N/mm2, mu = 0.25.
        // Hands not printed.
        Published {
            file: "seed001_9x40.toml",
            teeth: [9, 40],
            hands: None,
            module: Module::OuterTransverse(9.0),
            face_width_mm: Some(54.0),
            spiral_angle_deg: 35.0,
            pressure_angle_deg: Some(20.0),
            shaft_angle_deg: 90.0,
            pitch_angles_deg: Some(([13.0, 77.0], 0.5)),
            pitch_diameters_mm: None,
            material: Some((207.0, 0.25)),
        },
        // Seed 002 (shared/seeds/002_c3ebbaa7232b9d9f.txt), Table 1 "Some parameters of a
        // mating pair of the spiral bevel gears": 9/37, module 4.5 mm (outer transverse:
        // pitch diameters 40.5/166.5 mm = 4.5 z), pitch cone angles 13.671/76.329 deg,
        // shaft angle 90 deg, pressure angle 20 deg, spiral angle 35 deg. Section 3.1:
        // C45, nu = 0.285, E = 2.07e5 N/mm2. Face width and hands not printed.
        Published {
            file: "seed002_9x37.toml",
            teeth: [9, 37],
            hands: None,
            module: Module::OuterTransverse(4.5),
            face_width_mm: None,
            spiral_angle_deg: 35.0,
            pressure_angle_deg: Some(20.0),
            shaft_angle_deg: 90.0,
            pitch_angles_deg: Some(([13.671, 76.329], 0.001)),
            pitch_diameters_mm: Some([40.5, 166.5]),
            material: Some((207.0, 0.285)),
        },
        // Seed 003 (shared/seeds/003_3a2dfd66c9e52dfd.txt), Table 3 "Parameters of the
        // spiral bevel gear": 16/27, module 4.25 mm (kind not stated, taken as outer
        // transverse), face width 12 mm, pressure angle 20 deg, spiral angle 30 deg, shaft
        // angle 90 deg, hands pinion left / gear right. Section 4.2: E = 210 GPa, nu = 0.377.
        Published {
            file: "seed003_16x27.toml",
            teeth: [16, 27],
            hands: Some([Left, Right]),
            module: Module::OuterTransverse(4.25),
            face_width_mm: Some(12.0),
            spiral_angle_deg: 30.0,
            pressure_angle_deg: Some(20.0),
            shaft_angle_deg: 90.0,
            pitch_angles_deg: None,
            pitch_diameters_mm: None,
            material: Some((210.0, 0.377)),
        },
        // Seed 004 (shared/seeds/004_795ad724b614ec44.txt), Table 2 "Geometric Parameters
        // of the Spiral Bevel Gear Pair": 23/86, module 3.9 mm (kind not stated, taken as
        // outer transverse), normal pressure angle 25 deg, midpoint spiral angle 25 deg,
        // hands pinion right / gear left, shaft angle 90 deg, face width 37 mm. No material.
        Published {
            file: "seed004_23x86.toml",
            teeth: [23, 86],
            hands: Some([Right, Left]),
            module: Module::OuterTransverse(3.9),
            face_width_mm: Some(37.0),
            spiral_angle_deg: 25.0,
            pressure_angle_deg: Some(25.0),
            shaft_angle_deg: 90.0,
            pitch_angles_deg: None,
            pitch_diameters_mm: None,
            material: None,
        },
    ]
}

/// One seed pair's checks: the lines of its report and the mismatches.
struct Checks<'a> {
    file: &'a str,
    report: String,
    errors: &'a mut Vec<String>,
}

impl Checks<'_> {
    /// `value` from the file (or derived from published data), `expected` as
    /// published or derived from published data.
    fn check(&mut self, what: &str, value: f64, expected: f64, tol: f64) {
        let ok = (value - expected).abs() <= tol;
        self.report += &format!(
            "  {what:44} {value:>10.4}  expected {expected:>10.4} ± {tol:<7.1e} {}\n",
            if ok { "ok" } else { "MISMATCH" }
        );
        if !ok {
            self.errors.push(format!(
                "{}: {what}: {value}, expected {expected} ± {tol}",
                self.file
            ));
        }
    }
}

#[test]
fn seed_pairs_match_their_published_data() {
    let mut errors = Vec::new();
    for s in published() {
        let path = Path::new(REFERENCE).join(s.file);
        let p = match load_pair(&path) {
            Ok(p) => p,
            Err(e) => {
                errors.push(format!("{}: {e}", s.file));
                continue;
            }
        };
        let mut c = Checks {
            file: s.file,
            report: format!("{}\n", s.file),
            errors: &mut errors,
        };
        let b = check_teeth_angles_and_hands(&mut c, &s, &p);
        let (g1, g2) = check_pitch_angles(&mut c, &s, &p);
        check_module(&mut c, &s, &p, b, g1, g2);
        check_material(&mut c, &s, &p);
        print!("{}", c.report);
    }
    assert!(
        errors.is_empty(),
        "published values not kept:\n{}",
        errors.join("\n")
    );
}

/// Teeth, shaft and spiral angles, face width, pressure angles and hands;
/// returns the face width the conversions use (printed, else the file's), mm.
fn check_teeth_angles_and_hands(c: &mut Checks, s: &Published, p: &PairData) -> f64 {
    let (pin, whl) = (p.member(Member::Pinion), p.member(Member::Wheel));
    let deg = f64::to_degrees;
    c.check("pinion teeth", pin.teeth as f64, s.teeth[0] as f64, 0.0);
    c.check("wheel teeth", whl.teeth as f64, s.teeth[1] as f64, 0.0);
    c.check(
        "shaft angle, deg",
        deg(p.shaft_angle),
        s.shaft_angle_deg,
        1e-9,
    );
    c.check(
        "mean spiral angle, deg",
        deg(p.spiral_angle),
        s.spiral_angle_deg,
        1e-9,
    );
    let b = match s.face_width_mm {
        Some(b) => {
            c.check("face width, mm", p.face_width * 1e3, b, 1e-9);
            b
        }
        None => p.face_width * 1e3,
    };
    if let Some(a) = s.pressure_angle_deg {
        c.check(
            "drive pressure angle, deg",
            deg(p.pressure_angle[0]),
            a,
            1e-9,
        );
        c.check(
            "coast pressure angle, deg",
            deg(p.pressure_angle[1]),
            a,
            1e-9,
        );
    }
    if let Some(h) = s.hands {
        c.check(
            "pinion hand (right = 1)",
            (pin.hand == Hand::Right) as u8 as f64,
            (h[0] == Hand::Right) as u8 as f64,
            0.0,
        );
        c.check(
            "wheel hand (right = 1)",
            (whl.hand == Hand::Right) as u8 as f64,
            (h[1] == Hand::Right) as u8 as f64,
            0.0,
        );
    }
    b
}

/// Pitch angles from the tooth numbers, tan γ₁ = sin Σ / (z₂/z₁ + cos Σ),
/// against the printed ones and the file's; returns (γ₁, γ₂), rad.
fn check_pitch_angles(c: &mut Checks, s: &Published, p: &PairData) -> (f64, f64) {
    let (pin, whl) = (p.member(Member::Pinion), p.member(Member::Wheel));
    let deg = f64::to_degrees;
    let sigma = s.shaft_angle_deg.to_radians();
    let (z1, z2) = (s.teeth[0] as f64, s.teeth[1] as f64);
    let g1 = (sigma.sin() / (z2 / z1 + sigma.cos())).atan();
    let g2 = sigma - g1;
    if let Some((a, tol)) = s.pitch_angles_deg {
        c.check(
            "pinion pitch angle from teeth vs printed",
            deg(g1),
            a[0],
            tol,
        );
        c.check(
            "wheel pitch angle from teeth vs printed",
            deg(g2),
            a[1],
            tol,
        );
    }
    c.check(
        "pinion pitch angle, deg",
        deg(pin.pitch_angle),
        deg(g1),
        1e-3,
    );
    c.check(
        "wheel pitch angle, deg",
        deg(whl.pitch_angle),
        deg(g2),
        1e-3,
    );
    (g1, g2)
}

/// The module the paper gives (outer transverse, or mean normal with the
/// mean cone distance) against the file's cone distances and module; `b`
/// the face width, mm, and (γ₁, γ₂) the pitch angles from the teeth, rad.
fn check_module(c: &mut Checks, s: &Published, p: &PairData, b: f64, g1: f64, g2: f64) {
    let (z1, z2) = (s.teeth[0] as f64, s.teeth[1] as f64);
    let beta = s.spiral_angle_deg.to_radians();
    match s.module {
        Module::OuterTransverse(mte) => {
            // R_e = m_te z₁ / (2 sin γ₁), R_m = R_e − b/2, m_n = 2 R_m sin γ₁ cos β / z₁.
            let re = mte * z1 / (2.0 * g1.sin());
            let rm = re - 0.5 * b;
            let mn = 2.0 * rm * g1.sin() * beta.cos() / z1;
            c.check(
                "outer cone distance, mm",
                p.outer_cone_distance() * 1e3,
                re,
                1e-3,
            );
            c.check(
                "mean cone distance, mm",
                p.mean_cone_distance * 1e3,
                rm,
                1e-3,
            );
            c.check(
                "mean normal module, mm",
                p.normal_module * 1e3,
                mn,
                1e-4 * mn,
            );
            c.check(
                "outer transverse module from file, mm",
                2.0 * p.outer_cone_distance() * 1e3 * g1.sin() / z1,
                mte,
                1e-4 * mte,
            );
            if let Some(d) = s.pitch_diameters_mm {
                c.check(
                    "pinion outer pitch diameter m_te z1, mm",
                    mte * z1,
                    d[0],
                    1e-9,
                );
                c.check(
                    "wheel outer pitch diameter m_te z2, mm",
                    mte * z2,
                    d[1],
                    1e-9,
                );
                c.check(
                    "wheel outer pitch diameter from R_e, mm",
                    2.0 * re * g2.sin(),
                    d[1],
                    1e-3,
                );
            }
        }
        Module::MeanNormal {
            module,
            mean_cone_distance,
        } => {
            c.check(
                "mean normal module, mm",
                p.normal_module * 1e3,
                module,
                1e-9,
            );
            c.check(
                "mean cone distance, mm",
                p.mean_cone_distance * 1e3,
                mean_cone_distance,
                1e-9,
            );
            let mn = 2.0 * mean_cone_distance * g1.sin() * beta.cos() / z1;
            c.check(
                "published m_n vs 2 R_m sin g1 cos b / z1",
                module,
                mn,
                1e-3 * mn,
            );
        }
    }
}

/// Young's modulus and Poisson ratio of both members, where printed.
fn check_material(c: &mut Checks, s: &Published, p: &PairData) {
    let (pin, whl) = (p.member(Member::Pinion), p.member(Member::Wheel));
    if let Some((e, nu)) = s.material {
        for (n, d) in [("pinion", pin), ("wheel", whl)] {
            c.check(
                &format!("{n} Young's modulus, GPa"),
                d.youngs_modulus * 1e-9,
                e,
                1e-9,
            );
            c.check(&format!("{n} Poisson ratio"), d.poisson_ratio, nu, 1e-12);
        }
    }
}
