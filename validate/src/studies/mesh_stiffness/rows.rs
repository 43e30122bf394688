//! The stiffnesses at one operating torque: every FE and LTCA level's
//! tangent and secant in N/m, against the finest FE level, with the FE
//! levels' Richardson extrapolation; and the FE levels' costs.

use super::{kappas, loaded_pairs, FeLevelCost, ModelStiffness, TorqueStiffness};
use crate::studies::convergence::{richardson, LevelResult, MIN_ORDER};
use anyhow::Context;
use geometry::scene::MeshLevel;
use solver::ltca::PositionResult;
use solver::lumped::from_ltca::tangent_torques;

/// Flank elements (profile, face) of the scene's mesh level `level`.
fn level_elements(sc: &geometry::scene::Scene, level: &str) -> [u32; 2] {
    let e = match MeshLevel::from_name(level) {
        Some(MeshLevel::Medium) => sc.mesh.medium(),
        Some(MeshLevel::Reference) => sc.mesh.reference,
        _ => sc.mesh.reduced_order,
    };
    [e.profile, e.face]
}

/// The stiffnesses at operating torque `t`: every FE level's and every
/// LTCA level's, in N/m with the reduced LTCA's levers, against the
/// finest FE level, and the FE levels' Richardson extrapolation.
pub(super) fn torque_row(
    t: f64,
    sc: &geometry::scene::Scene,
    torques: &[f64],
    fe: &[LevelResult],
    ltca: &[(MeshLevel, PositionResult)],
) -> anyhow::Result<TorqueStiffness> {
    let t3 = tangent_torques(t);
    let mid = torques
        .iter()
        .position(|&x| x == t)
        .context("operating torque solved")?;
    let red = &ltca.first().context("the reduced level's LTCA")?.1.loads[mid];
    let total: f64 = red.pair_force.iter().map(|f| f.1).sum();
    let levers = [t / total, red.wheel_torque_nm / total];
    let mut models = fe_models(torques, fe, t3, mid, levers)?;
    models.extend(ltca_models(sc, torques, ltca, t3, mid, levers)?);
    if let Some(finest) = fe.last().map(|l| l.level.clone()) {
        let kf = models
            .iter()
            .find(|m| m.model == "fe" && m.level == finest)
            .map(|m| m.tangent_n_per_m)
            .unwrap_or(f64::NAN);
        for m in &mut models {
            m.tangent_vs_finest_fe_pct = Some((m.tangent_n_per_m - kf) / kf * 100.0);
        }
    }
    let fit = (fe.len() == 3)
        .then(|| {
            let k: Vec<f64> = models
                .iter()
                .filter(|m| m.model == "fe")
                .map(|m| m.tangent_n_per_m)
                .collect();
            richardson([fe[0].h, fe[1].h, fe[2].h], [k[0], k[1], k[2]])
        })
        .flatten()
        .filter(|&(p, _)| p >= MIN_ORDER);
    Ok(TorqueStiffness {
        torque_nm: t,
        tangent_torques_nm: t3,
        levers_m: levers,
        models,
        fe_extrapolated_tangent_n_per_m: fit.map(|f| f.1),
        fe_observed_order: fit.map(|f| f.0),
    })
}

/// Each FE level's tangent and secant at the tangent torques `t3` (`mid`
/// the operating torque's index in `torques`), in N/m with `levers`.
fn fe_models(
    torques: &[f64],
    fe: &[LevelResult],
    t3: [f64; 3],
    mid: usize,
    levers: [f64; 2],
) -> anyhow::Result<Vec<ModelStiffness>> {
    let to_n_per_m = |kappa: f64| kappa / (levers[0] * levers[1]);
    let mut models = Vec::new();
    for l in fe {
        let te: Vec<f64> = l.te_urad.iter().map(|v| v * 1e-6).collect();
        let [kt, ks] = kappas(torques, &te, t3, l.unloaded_te_urad * 1e-6)
            .with_context(|| format!("FE level {}", l.level))?;
        let check = (l.te_check_urad.len() == torques.len())
            .then(|| {
                let tc: Vec<f64> = l.te_check_urad.iter().map(|v| v * 1e-6).collect();
                kappas(torques, &tc, t3, l.unloaded_te_urad * 1e-6).ok()
            })
            .flatten()
            .map(|[k, _]| to_n_per_m(k));
        models.push(ModelStiffness {
            model: "fe".into(),
            level: l.level.clone(),
            elements: [l.profile_elements, l.face_elements],
            te_urad: l.te_urad[mid],
            unloaded_te_urad: l.unloaded_te_urad,
            tangent_nm_per_rad: kt,
            secant_nm_per_rad: ks,
            tangent_n_per_m: to_n_per_m(kt),
            secant_n_per_m: to_n_per_m(ks),
            tangent_check_n_per_m: check,
            pairs_in_contact: None,
            tangent_vs_finest_fe_pct: None,
        });
    }
    Ok(models)
}

/// Each LTCA level's tangent and secant at the tangent torques `t3` (`mid`
/// the operating torque's index in `torques`), in N/m with `levers`.
fn ltca_models(
    sc: &geometry::scene::Scene,
    torques: &[f64],
    ltca: &[(MeshLevel, PositionResult)],
    t3: [f64; 3],
    mid: usize,
    levers: [f64; 2],
) -> anyhow::Result<Vec<ModelStiffness>> {
    let to_n_per_m = |kappa: f64| kappa / (levers[0] * levers[1]);
    let elements = |level: &str| level_elements(sc, level);
    let mut models = Vec::new();
    for (level, r) in ltca {
        let te: Vec<f64> = r.loads.iter().map(|l| l.te).collect();
        let [kt, ks] = kappas(torques, &te, t3, r.utca_te)
            .with_context(|| format!("LTCA level {}", level.name()))?;
        models.push(ModelStiffness {
            model: "ltca".into(),
            level: level.name().into(),
            elements: elements(level.name()),
            te_urad: te[mid] * 1e6,
            unloaded_te_urad: r.utca_te * 1e6,
            tangent_nm_per_rad: kt,
            secant_nm_per_rad: ks,
            tangent_n_per_m: to_n_per_m(kt),
            secant_n_per_m: to_n_per_m(ks),
            tangent_check_n_per_m: None,
            pairs_in_contact: Some(t3.map(|x| {
                let i = torques.iter().position(|&y| y == x).unwrap_or(mid);
                loaded_pairs(&r.loads[i])
            })),
            tangent_vs_finest_fe_pct: None,
        });
    }
    Ok(models)
}

/// Sizes and costs of the FE levels solved.
pub(super) fn fe_level_costs(fe: &[LevelResult]) -> Vec<FeLevelCost> {
    fe.iter()
        .map(|l| FeLevelCost {
            level: l.level.clone(),
            elements: [l.profile_elements, l.face_elements],
            dofs: l.dofs,
            constraints: l.constraints,
            factor_gb: l.factor_bytes.map(|b| b as f64 / 1e9),
            estimated_factor_gb: l.estimated_factor_bytes.map(|b| b / 1e9),
            factor_s: l.factor_s,
            position_s: l.position_s,
            unloaded_te_urad: l.unloaded_te_urad,
            utca_te_urad: l.utca_te_urad,
        })
        .collect()
}
