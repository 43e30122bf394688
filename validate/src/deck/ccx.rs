//! Runs CalculiX (`ccx`, Debian's `calculix-ccx`) on a written deck and
//! reads the printed results back from its `.dat` file.

use std::path::{Path, PathBuf};

/// Errors of a CalculiX run.
#[derive(Debug, thiserror::Error)]
pub enum CcxError {
    #[error("cannot start `{program}` ({source}); `make setup` installs Debian's calculix-ccx")]
    Missing {
        program: String,
        source: std::io::Error,
    },
    #[error("CalculiX failed on {deck} (exit {code:?}): {tail}")]
    Failed {
        deck: PathBuf,
        code: Option<i32>,
        tail: String,
    },
    #[error("{dat}: no {what} of set {set} at the end of step {step}")]
    NoResult {
        dat: PathBuf,
        what: String,
        set: String,
        step: usize,
    },
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// One printed block of the `.dat` file: what (the words before the
/// parenthesis, e.g. "displacements", "forces", "total force"), the set,
/// the total time and its rows of numbers (node number first, except for
/// totals).
#[derive(Debug, Clone, PartialEq)]
pub struct Printed {
    pub what: String,
    pub set: String,
    pub time: f64,
    pub rows: Vec<Vec<f64>>,
}

/// The blocks of a `.dat` file in the order printed.
pub fn parse_dat(text: &str) -> Vec<Printed> {
    let mut out: Vec<Printed> = Vec::new();
    for line in text.lines() {
        let t = line.trim();
        if t.is_empty() {
            continue;
        }
        if let (Some(at_set), Some(at_time)) = (t.find(" for set "), t.find(" and time ")) {
            let what = t[..t.find('(').unwrap_or(at_set)].trim().to_string();
            let set = t[at_set + 9..at_time].trim().to_string();
            let time = t[at_time + 10..].trim().parse().unwrap_or(f64::NAN);
            out.push(Printed {
                what,
                set,
                time,
                rows: Vec::new(),
            });
            continue;
        }
        let nums: Option<Vec<f64>> = t.split_whitespace().map(|w| w.parse().ok()).collect();
        match (nums, out.last_mut()) {
            (Some(v), Some(b)) if !v.is_empty() => b.rows.push(v),
            _ => {}
        }
    }
    out
}

/// The last block of `what` for `set` printed in step `step` (1-based;
/// every step of the deck lasts a time of 1, so step k ends at time k).
pub fn at_step_end<'a>(
    blocks: &'a [Printed],
    what: &str,
    set: &str,
    step: usize,
) -> Option<&'a Printed> {
    blocks
        .iter()
        .rev()
        .find(|b| b.what == what && b.set == set && (b.time - step as f64).abs() < 1e-6)
}

/// The outcome of one run.
#[derive(Debug, Clone)]
pub struct CcxRun {
    pub dat: PathBuf,
    pub blocks: Vec<Printed>,
    /// Process CPU time of the run (children), s.
    pub cpu_s: f64,
}

impl CcxRun {
    /// Component `dof` (1..=3) of `what` at the single node of `set` at the
    /// end of step `step`.
    pub fn node_value(
        &self,
        what: &str,
        set: &str,
        step: usize,
        dof: usize,
    ) -> Result<f64, CcxError> {
        at_step_end(&self.blocks, what, set, step)
            .and_then(|b| b.rows.first())
            .and_then(|r| r.get(dof))
            .copied()
            .ok_or_else(|| CcxError::NoResult {
                dat: self.dat.clone(),
                what: what.into(),
                set: set.into(),
                step,
            })
    }
}

/// Runs `ccx` on `<dir>/<job>.inp` (written before) in `dir`, with
/// `threads` solver threads.
pub fn run(dir: &Path, job: &str, threads: usize) -> Result<CcxRun, CcxError> {
    let program = std::env::var("CCX").unwrap_or_else(|_| "ccx".into());
    let before = children_cpu_s();
    let mut cmd = std::process::Command::new(&program);
    cmd.arg("-i")
        .arg(job)
        .current_dir(dir)
        .env("OMP_NUM_THREADS", threads.to_string())
        .env("CCX_NPROC_EQUATION_SOLVER", threads.to_string());
    let out = formats::interrupt::output(&mut cmd).map_err(|source| CcxError::Missing {
        program: program.clone(),
        source,
    })?;
    let stdout = String::from_utf8_lossy(&out.stdout);
    let deck = dir.join(format!("{job}.inp"));
    if !out.status.success() || stdout.contains("*ERROR") {
        let text = format!("{stdout}{}", String::from_utf8_lossy(&out.stderr));
        let tail: Vec<&str> = text
            .lines()
            .filter(|l| l.contains("ERROR") || l.contains("error"))
            .take(5)
            .collect();
        let tail = if tail.is_empty() {
            text.lines().rev().take(5).collect::<Vec<_>>().join(" | ")
        } else {
            tail.join(" | ")
        };
        return Err(CcxError::Failed {
            deck,
            code: out.status.code(),
            tail,
        });
    }
    let dat = dir.join(format!("{job}.dat"));
    let text = std::fs::read_to_string(&dat)?;
    Ok(CcxRun {
        blocks: parse_dat(&text),
        dat,
        cpu_s: children_cpu_s() - before,
    })
}

/// CPU time (user + system) of this process's waited-for children, s.
fn children_cpu_s() -> f64 {
    // SAFETY: getrusage writes into the zeroed struct it is given.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut u) };
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dat_blocks_of_two_steps_are_found_by_their_end_time() {
        let text = "
 displacements (vx,vy,vz) for set NROT and time  0.1000000E+01

         9  0.000000E+00  0.000000E+00  1.000000E-04

 total force (fx,fy,fz) for set WBORE and time  0.1000000E+01

        1.500000E+00 -2.000000E+00  3.000000E+00

 displacements (vx,vy,vz) for set NROT and time  0.1500000E+01

         9  0.000000E+00  0.000000E+00  1.100000E-04

 displacements (vx,vy,vz) for set NROT and time  0.2000000E+01

         9  0.000000E+00  0.000000E+00  1.200000E-04
";
        let b = parse_dat(text);
        assert_eq!(b.len(), 4);
        assert_eq!(b[1].what, "total force");
        assert_eq!(b[1].rows, vec![vec![1.5, -2.0, 3.0]]);
        let run = CcxRun {
            dat: "x.dat".into(),
            blocks: b,
            cpu_s: 0.0,
        };
        assert_eq!(
            run.node_value("displacements", "NROT", 1, 3).unwrap(),
            1.0e-4
        );
        assert_eq!(
            run.node_value("displacements", "NROT", 2, 3).unwrap(),
            1.2e-4
        );
        assert!(run.node_value("displacements", "NROT", 3, 3).is_err());
        assert!(run.node_value("forces", "NROT", 1, 3).is_err());
    }
}
