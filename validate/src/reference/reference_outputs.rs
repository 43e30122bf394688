//! The reference stage's output files: `te.csv`, the contact-pattern VTU,
//! the per-load summaries, the unloaded check, and the copy of a reused
//! blank's files into a new result set.

use super::reference_root_stress::root_stress_summary;
use super::reference_summary::{LoadSummary, UnloadedCheck};
use crate::reference::reference_ltca::{Member, PositionResult};
use anyhow::Context;
use formats::columns;
use formats::output::write_atomic;
use solver::ltca::mean_ptp;
use std::fmt::Write as _;
use std::path::Path;

pub(crate) fn unloaded_check(res: &[PositionResult], utca: &[f64]) -> UnloadedCheck {
    let r: Vec<f64> = res.iter().map(|p| p.unloaded_te * 1e6).collect();
    let u: Vec<f64> = utca.iter().map(|t| t * 1e6).collect();
    let d: Vec<f64> = r.iter().zip(&u).map(|(a, b)| a - b).collect();
    let (rm, rp) = mean_ptp(&r);
    let (um, up) = mean_ptp(&u);
    UnloadedCheck {
        torque_nm: crate::reference::reference_ltca::UNLOADED_TORQUE_NM,
        max_abs_difference_urad: d.iter().map(|x| x.abs()).fold(0.0, f64::max),
        mean_difference_urad: d.iter().sum::<f64>() / d.len().max(1) as f64,
        utca_te_mean_urad: um,
        utca_te_ptp_urad: up,
        reference_te_mean_urad: rm,
        reference_te_ptp_urad: rp,
    }
}

/// Copies the files (not the directories) of `from` into `to`: a reused
/// blank's results into the new set.
pub(crate) fn copy_files(from: &Path, to: &Path) -> anyhow::Result<()> {
    std::fs::create_dir_all(to)?;
    for e in std::fs::read_dir(from)? {
        let e = e?;
        if e.file_type()?.is_file() {
            let (a, b) = (e.path(), to.join(e.file_name()));
            std::fs::copy(&a, &b)
                .with_context(|| format!("cannot copy {} to {}", a.display(), b.display()))?;
        }
    }
    Ok(())
}

/// The pressure envelope on the pinion flank nodes (member frame, m) as a
/// VTK unstructured grid of vertices with the point field `pressure_mpa`,
/// for ParaView.
pub fn pattern_vtu(pts: &[([f64; 3], f64)]) -> String {
    let n = pts.len();
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n",
    );
    let _ = writeln!(s, "<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{n}\">");
    s.push_str("<PointData Scalars=\"pressure_mpa\">\n<DataArray type=\"Float64\" Name=\"pressure_mpa\" format=\"ascii\">\n");
    for (_, v) in pts {
        let _ = writeln!(s, "{}", v * 1e-6);
    }
    s.push_str("</DataArray>\n</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
    for (p, _) in pts {
        let _ = writeln!(s, "{} {} {}", p[0], p[1], p[2]);
    }
    s.push_str("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for i in 0..n {
        let _ = writeln!(s, "{i}");
    }
    s.push_str("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for i in 0..n {
        let _ = writeln!(s, "{}", i + 1);
    }
    // VTK_VERTEX = 1.
    s.push_str("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for _ in 0..n {
        s.push_str("1\n");
    }
    s.push_str("</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
    s
}

/// Prints a factored body's size: dofs, factor values, the part kept.
pub(crate) fn report_factor(name: &str, m: Option<&Member>) {
    if let Some(c) = m.map(|m| &m.compliance) {
        let gb = |n: usize| n as f64 * 8.0 / 1e9;
        eprintln!(
            "reference: {name}: {} dofs, factor {:.2} GB in {:.0} s, {:.2} GB kept on the paths of the contact and fillet nodes",
            c.dofs_free,
            gb(c.factor_nnz[1]),
            c.factor_s,
            gb(c.factor_nnz[0])
        );
    }
}

/// Per-torque statistics of the positions `res`, solved at the penalty
/// factors `penalty` = [p, p_c] (the TE at p and at the check factor p_c).
/// Per torque: the TE statistics, the penalty check, pressure, balance,
/// margins and root stress of the positions `res`; `rotation` turns a
/// pinion angle into the sweep's rotation (deg).
pub(crate) fn load_summaries(
    res: &[PositionResult],
    torques: &[f64],
    penalty: [f64; 2],
    rotation: &dyn Fn(f64) -> f64,
) -> Vec<LoadSummary> {
    let n = res.len().max(1) as f64;
    let [p, pc] = penalty;
    torques
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            let te: Vec<f64> = res.iter().map(|r| r.loads[k].te).collect();
            let (mean, ptp) = mean_ptp(&te);
            let penalty_max = res
                .iter()
                .map(|r| (r.loads[k].te - r.loads[k].te_check).abs())
                .fold(0.0, f64::max);
            let check: Vec<f64> = res.iter().map(|r| r.loads[k].te_check).collect();
            let (check_mean, check_ptp) = mean_ptp(&check);
            let rigid = (p != pc).then(|| {
                mean_ptp(
                    &te.iter()
                        .zip(&check)
                        .map(|(a, b)| rigid_limit(*a, *b, p, pc))
                        .collect::<Vec<f64>>(),
                )
            });
            LoadSummary {
                torque_nm: t,
                te_mean_urad: mean * 1e6,
                te_ptp_urad: ptp * 1e6,
                penalty_difference_pct: penalty_max / mean.abs() * 100.0,
                penalty_difference_max_urad: penalty_max * 1e6,
                te_check_mean_urad: Some(check_mean * 1e6),
                te_check_ptp_urad: Some(check_ptp * 1e6),
                te_rigid_mean_urad: rigid.map(|r| r.0 * 1e6),
                te_rigid_ptp_urad: rigid.map(|r| r.1 * 1e6),
                max_pressure_mpa: res
                    .iter()
                    .map(|r| r.loads[k].max_pressure_pa)
                    .fold(0.0, f64::max)
                    * 1e-6,
                torque_balance_max: res
                    .iter()
                    .map(|r| r.loads[k].torque_balance.abs())
                    .fold(0.0, f64::max),
                band_margin_min_um: res
                    .iter()
                    .map(|r| r.loads[k].band_margin_m)
                    .fold(f64::INFINITY, f64::min)
                    * 1e6,
                search_margin_min_um: res
                    .iter()
                    .map(|r| r.loads[k].search_margin_m)
                    .collect::<Option<Vec<f64>>>()
                    .map(|v| v.into_iter().fold(f64::INFINITY, f64::min) * 1e6),
                cpu_s_per_position: res.iter().map(|r| r.cpu_s).sum::<f64>() / n,
                root_stress: root_stress_summary(res, k, rotation),
            }
        })
        .collect()
}

/// The TE extrapolated to an infinite penalty from the TEs `te` at
/// penalty factor `p` and `te_check` at `p_check` (p ≠ p_check), for
/// TE(p) = TE∞ + c/p: TE∞ = (p TE(p) − p_c TE(p_c)) / (p − p_c).
pub fn rigid_limit(te: f64, te_check: f64, p: f64, p_check: f64) -> f64 {
    (p * te - p_check * te_check) / (p - p_check)
}

pub(crate) fn write_te_csv(
    path: &Path,
    res: &[PositionResult],
    utca: &[f64],
    flank: &geometry::flank::Flank,
    start: f64,
    direction: f64,
) -> anyhow::Result<()> {
    let mut s = format!(
        "{},{},te_unloaded_urad,unloaded_xi,unloaded_eta",
        columns::PINION_ROTATION_DEG,
        columns::UTCA_TE_URAD
    );
    if let Some(r) = res.first() {
        for l in &r.loads {
            write!(s, ",{}", columns::te_at_urad(l.torque_nm))?;
        }
    }
    s.push('\n');
    for (r, u) in res.iter().zip(utca) {
        let (l, d) = flank.gen.frame.axial(&r.unloaded_point);
        let (xi, eta) = flank.bounds.to_unit(l, d);
        write!(
            s,
            "{},{},{},{xi},{eta}",
            ((r.phi - start) * direction).to_degrees(),
            u * 1e6,
            r.unloaded_te * 1e6
        )?;
        for l in &r.loads {
            write!(s, ",{}", l.te * 1e6)?;
        }
        s.push('\n');
    }
    write_atomic(path, s.as_bytes())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::rigid_limit;

    /// Springs in series: TE(p) = TE∞ + c/p at two factors gives TE∞
    /// back exactly; equal TEs (no penalty share) give themselves.
    #[test]
    fn rigid_limit_of_a_series_penalty_spring_is_its_intercept() {
        let te = |p: f64| 350e-6 + 0.8e-3 / p;
        let inf = rigid_limit(te(100.0), te(200.0), 100.0, 200.0);
        assert!((inf - 350e-6).abs() < 1e-15, "{inf}");
        assert_eq!(rigid_limit(2e-4, 2e-4, 100.0, 200.0), 2e-4);
    }
}
