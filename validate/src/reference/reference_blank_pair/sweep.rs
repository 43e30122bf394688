//! A blank pair's sweep over its positions: each from the cache or solved
//! (the bodies loaded and factored at the first position solved), and the
//! report of a cache comparison.

use super::{Bodies, BodyKey, PairMeshes, Run, Swept};
use crate::reference::position_cache::{self, Cached};
use crate::reference::reference_ltca::{Member, ReferencePair};
use crate::reference::reference_options::COMPARE_TOLERANCE;
use crate::reference::reference_outputs::report_factor;
use crate::reference::reference_summary::CacheComparison;
use anyhow::Context;
use formats::added_files::{add_json, Dependence};
use geometry::design::Member as Which;
use std::path::Path;

impl Run<'_> {
    /// Every position of the sweep (this shard's with `--shard`): from the
    /// cache, or solved (and cached; compared with the cache under
    /// `--compare-cache`), the bodies loaded and factored at the first
    /// position solved.
    pub(super) fn sweep(
        &self,
        name: &str,
        positions: &[f64],
        cache_dir: &Path,
        meshes: &PairMeshes,
        bodies: &mut Bodies,
        keys: &[BodyKey],
    ) -> anyhow::Result<Swept> {
        let (opt, sc) = (self.opt, &self.scene.scene);
        let mut solved = false;
        let mut before = [(0, 0.0); 2];
        let bar = indicatif::ProgressBar::new(positions.len() as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "reference {msg} [{bar:30}] {pos}/{len} positions, eta {eta}",
            )?
            .progress_chars("=> "),
        );
        bar.set_message(name.to_string());
        let t_sweep = std::time::Instant::now();
        let mut res = Vec::with_capacity(positions.len());
        let mut reused = 0;
        let mut comparison = CacheComparison {
            tolerance: COMPARE_TOLERANCE,
            ..Default::default()
        };
        for (i, &phi) in positions.iter().enumerate() {
            if opt.shard.is_some_and(|(k, n)| i % n != k) {
                bar.inc(1);
                continue;
            }
            let cached = cache_dir.join(format!(
                "phi_{}udeg.json",
                (phi.to_degrees() * 1e6).round() as i64
            ));
            let from_cache = match position_cache::read(&cached) {
                Cached::Valid(r) => Some(*r),
                Cached::Changed { found, listed } => {
                    eprintln!(
                        "reference {name}: {} is not the result its checksum was made of (SHA-256 {found}, listed {listed}); solving the position again",
                        cached.display()
                    );
                    None
                }
                Cached::Absent => None,
            }
            .filter(|r| r.loads.len() == sc.pinion_torque_nm.len());
            if opt.compare_cache && from_cache.is_none() {
                comparison.positions_without_cache += 1;
                bar.inc(1);
                continue;
            }
            if let (false, Some(r)) = (opt.compare_cache, &from_cache) {
                res.push(r.clone());
                reused += 1;
                bar.inc(1);
                continue;
            }
            if !solved {
                self.load_bodies(meshes, bodies, keys)?;
                for (b, m) in before.iter_mut().zip([&bodies.pinion, &bodies.wheel]) {
                    let c = &m.as_ref().expect("factored above").1.compliance;
                    *b = (c.solves, c.solve_s);
                }
                solved = true;
            }
            let mut pair = ReferencePair {
                pinion: &mut bodies.pinion.as_mut().expect("pinion factored above").1,
                wheel: &mut bodies.wheel.as_mut().expect("wheel factored above").1,
                flanks: self.fp(),
                direction: self.direction,
                settings: opt.settings,
            };
            formats::stop_point::at("solving");
            let r = pair.position(phi, &sc.pinion_torque_nm).with_context(|| {
                format!(
                    "scene {}: reference LTCA {name} at pinion angle {:.3} deg",
                    sc.name,
                    phi.to_degrees()
                )
            })?;
            match &from_cache {
                Some(old) => comparison.add(&r, old),
                None => position_cache::write(&cached, &r)?,
            }
            if bar.is_hidden() {
                eprintln!(
                    "reference {name}: position {}/{}: {} of {} constraints solved, {} new nodes, TE {:.2} urad at {} N m, {:.1} s",
                    i + 1,
                    positions.len(),
                    r.constraints,
                    r.searched,
                    r.new_columns,
                    r.loads.last().map_or(0.0, |l| l.te * 1e6),
                    r.loads.last().map_or(0.0, |l| l.torque_nm),
                    r.cpu_s
                );
            }
            res.push(r);
            bar.inc(1);
        }
        bar.finish_and_clear();
        Ok(Swept {
            res,
            reused,
            comparison,
            solved,
            before,
            sweep_s: t_sweep.elapsed().as_secs_f64(),
        })
    }

    /// Makes `bodies` hold the bodies of `keys` (pinion, wheel): a body
    /// held with the same key (factored for another scene or blank pair of
    /// this run) is kept, any other is let go and the body read and
    /// factored, after checking that the factors this run will hold at
    /// once fit the memory (estimated from the meshes' node counts;
    /// unknown in manifests from before they were recorded).
    fn load_bodies(
        &self,
        meshes: &PairMeshes,
        bodies: &mut Bodies,
        keys: &[BodyKey],
    ) -> anyhow::Result<()> {
        let opt = self.opt;
        for (slot, key) in [&mut bodies.pinion, &mut bodies.wheel]
            .into_iter()
            .zip(keys)
        {
            if slot.as_ref().is_some_and(|(k, _)| k != key) {
                *slot = None;
            }
        }
        let mut parts = Vec::new();
        if bodies.pinion.is_none() && meshes.dofs[0] > 0 {
            parts.push(("pinion", meshes.dofs[0]));
        }
        if bodies.wheel.is_none() && meshes.dofs[1] > 0 {
            parts.push(("wheel", meshes.dofs[1]));
        }
        formats::memory_estimate::check_fits(
            &self.what,
            &parts,
            opt.memory_bytes
                .or_else(fem::cholesky::available_memory_bytes),
        )?;
        formats::stop_point::at("reading");
        let [pm, wm] = &meshes.paths;
        for (k, (slot, which, path, teeth, name)) in [
            (
                &mut bodies.pinion,
                Which::Pinion,
                pm,
                &self.pinion_teeth[..],
                "pinion",
            ),
            (
                &mut bodies.wheel,
                Which::Wheel,
                wm,
                keys[1].teeth(),
                "wheel",
            ),
        ]
        .into_iter()
        .enumerate()
        {
            if slot.is_none() {
                eprintln!("reference: reading and factoring {}", path.display());
                let m = Member::load(path, &self.g, which, self.side, teeth, opt.block)?;
                report_factor(name, Some(&m));
                *slot = Some((keys[k].clone(), m));
            } else {
                eprintln!(
                    "reference: {name} factored already in this run (same mesh and teeth), kept"
                );
            }
        }
        Ok(())
    }

    /// `--compare-cache`: the comparison recorded beside the set it
    /// checked, and refused beyond [`COMPARE_TOLERANCE`].
    pub(super) fn report_comparison(
        &self,
        name: &str,
        comparison: &CacheComparison,
        odir: &Path,
    ) -> anyhow::Result<()> {
        if let Some(lock) = &self.lock {
            add_json(
                lock,
                &format!("{name}/compare_cache.json"),
                comparison,
                Dependence::OnSet,
            )?;
        }
        eprintln!(
            "reference {name}: {} positions solved anew against the cache ({} not cached): largest relative difference {:.2e} (TE {:.2e}, check-penalty TE {:.2e}, max pressure {:.2e}, search margin {:.2e}; torque balance {:.2e}), {} with other constraint counts",
            comparison.positions_compared,
            comparison.positions_without_cache,
            comparison.worst(),
            comparison.te,
            comparison.te_check,
            comparison.max_pressure,
            comparison.search_margin,
            comparison.torque_balance_abs,
            comparison.count_mismatches
        );
        if comparison.worst() > COMPARE_TOLERANCE || comparison.count_mismatches > 0 {
            anyhow::bail!(
                "reference {name}: positions solved now differ from the cache by {:.2e} (tolerance {COMPARE_TOLERANCE:e}) with {} constraint-count mismatches; see {}",
                comparison.worst(),
                comparison.count_mismatches,
                odir.join("compare_cache.json").display()
            );
        }
        Ok(())
    }
}
