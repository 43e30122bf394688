//! The SVG charts of `solver lumped`, beside its CSVs in
//! `<out>/<scene>/lumped/<pinion>_<wheel>/`:
//!
//! - `mesh_force.svg`: the dynamic mesh force Fₙ(t) = k(t) λ + c λ̇ (+ the
//!   impact pulse) over the kept mesh cycles, with the static force T₁/r₁;
//! - `accelerations.svg`: the bodies' accelerations Ẍ₁, Ÿ₁, Z̈₁, Ẍ₂, Ÿ₂, Z̈₂
//!   over the kept mesh cycles (the mesh normal's λ̈, two orders larger, is
//!   in `time_history.csv` and the summary);
//! - `bearing_spectrum.svg`: the amplitude spectrum of the pinion's and the
//!   wheel's resultant bearing-force fluctuation against the mesh order
//!   f / f_mesh, with the integer mesh orders marked.
//!
//! Time axes are in mesh cycles t·f_mesh; long records are drawn as min/max
//! envelopes ([`crate::multibody::load_run::envelope`]) so the peaks survive.

use crate::lumped::integrate::History;
use crate::lumped::response::Response;
use crate::multibody::load_run::envelope;
use charts::{te_curve, PlotError, Series};
use std::path::Path;

/// Time buckets of the time charts.
const BUCKETS: usize = 2000;

/// The chart files, in the order written.
pub const CHART_FILES: [&str; 3] = [
    "mesh_force.svg",
    "accelerations.svg",
    "bearing_spectrum.svg",
];

/// Writes the three charts of one blank pair; `first` is the first kept
/// sample of `h`, `static_force_n` = T₁/r₁, `max_order` the spectrum's range.
#[allow(clippy::too_many_arguments)]
pub fn write_plots(
    odir: &Path,
    label: &str,
    h: &History,
    first: usize,
    mesh_hz: f64,
    static_force_n: f64,
    r: &Response,
    max_order: f64,
) -> Result<(), PlotError> {
    let first = first.min(h.t.len());
    let cycles: Vec<f64> = h.t[first..].iter().map(|t| t * mesh_hz).collect();
    let line = |name: &str, x: Vec<f64>, y: Vec<f64>, dashed: bool| Series {
        name: name.into(),
        x,
        y,
        dashed,
    };
    let force: Vec<f64> = h.mesh[first..].iter().map(|m| m.force_n).collect();
    let (x, y) = envelope(&cycles, &force, BUCKETS);
    let span = [
        cycles.first().copied().unwrap_or(0.0),
        cycles.last().copied().unwrap_or(0.0),
    ];
    te_curve(
        &odir.join(CHART_FILES[0]),
        &format!("Dynamic mesh force, {label}"),
        "time (mesh cycles)",
        "mesh force Fn (N)",
        &[
            line("dynamic Fn", x, y, false),
            line("static T1/r1", span.to_vec(), vec![static_force_n; 2], true),
        ],
    )?;
    let names = [
        "pinion X", "pinion Y", "pinion Z", "wheel X", "wheel Y", "wheel Z",
    ];
    let dofs = [0, 1, 2, 4, 5, 6];
    let acc: Vec<Series> = names
        .iter()
        .zip(dofs)
        .map(|(name, i)| {
            let a: Vec<f64> = h.qdd[first..].iter().map(|q| q[i]).collect();
            let (x, y) = envelope(&cycles, &a, BUCKETS);
            line(name, x, y, false)
        })
        .collect();
    te_curve(
        &odir.join(CHART_FILES[1]),
        &format!("Body accelerations, {label}"),
        "time (mesh cycles)",
        "acceleration (m/s²)",
        &acc,
    )?;
    let order: Vec<f64> = r.bearing_spectrum.iter().map(|l| l[0]).collect();
    let pinion: Vec<f64> = r.bearing_spectrum.iter().map(|l| l[1]).collect();
    let wheel: Vec<f64> = r.bearing_spectrum.iter().map(|l| l[2]).collect();
    let top = pinion
        .iter()
        .chain(&wheel)
        .copied()
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max);
    let mut spectrum = vec![
        line("pinion bearing", order.clone(), pinion, false),
        line("wheel bearing", order, wheel, false),
    ];
    let mut m = 1.0;
    while m <= max_order {
        spectrum.push(line("mesh orders", vec![m, m], vec![0.0, top], true));
        m += 1.0;
    }
    te_curve(
        &odir.join(CHART_FILES[2]),
        &format!("Bearing-force spectrum, {label}"),
        "mesh order f / f_mesh",
        "force amplitude (N)",
        &spectrum,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lumped::integrate::MeshForceSample;

    #[test]
    fn three_charts_are_written_with_the_static_force_and_mesh_orders_marked() {
        let mesh_hz = 1000.0;
        let n = 400;
        let t: Vec<f64> = (0..n).map(|i| i as f64 / (100.0 * mesh_hz)).collect();
        let mesh = t
            .iter()
            .map(|&t| MeshForceSample {
                lambda_m: 1e-5,
                stiffness_n_per_m: 1e8,
                force_n: 1000.0 + 50.0 * (2.0 * std::f64::consts::PI * mesh_hz * t).sin(),
                impact_n: 0.0,
            })
            .collect();
        let qdd = t.iter().map(|&t| [t * 1e3; 8]).collect();
        let h = History {
            t: t.clone(),
            q: vec![[0.0; 8]; n],
            qd: vec![[0.0; 8]; n],
            qdd,
            mesh,
            steps: [n, 0],
            evaluations: 6 * n,
        };
        let r = Response {
            rms_acceleration: [1.0; 7],
            rms_velocity: [1e-3; 7],
            member_velocity_rms: [1e-3; 2],
            relative_normal_rms: 1.0,
            peak_to_peak: [1.0; 7],
            mesh_force: [1000.0, 950.0, 1050.0],
            bearing_rms: [1.0; 6],
            bearing_peaks: vec![(1.0, 20.0)],
            bearing_spectrum: (1..=30).map(|k| [k as f64 / 10.0, 1.0, 2.0]).collect(),
        };
        let dir = std::env::temp_dir().join(format!("lumped_plots_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        write_plots(&dir, "test", &h, 200, mesh_hz, 1000.0, &r, 3.0).unwrap();
        let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
        let texts: Vec<String> = CHART_FILES.iter().map(|f| read(f)).collect();
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(texts[0].contains("static T1/r1"));
        assert!(texts[1].contains("wheel Z"));
        assert!(texts[2].contains("mesh orders"));
        assert!(texts.iter().all(|t| t.starts_with("<svg")));
    }
}
