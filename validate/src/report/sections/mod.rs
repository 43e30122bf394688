//! The report's sections, each formatted from the result files of the
//! stage or study it reports: the sections after the loaded TE and the
//! unloaded TCA, in the order the report shows them.

pub mod ablation;
pub mod calibrated_variant;
pub mod compliant_bearings;
pub mod contact_laws;
pub mod contact_laws_load_run;
pub mod gearbox;
pub mod grid_convergence;
pub mod lightweight_revolution;
pub mod loaded_contact;
pub mod lumped;
pub mod lumped_fe_stiffness;
pub mod lumped_order_map;
pub mod lumped_seed003;
pub mod lumped_studies;
pub mod multibody_runs;
pub mod pattern_numbers;
pub mod rattle;
pub mod reference_uncertainty;
pub mod root_stress;
pub mod sensitivity;
pub mod stage_tradeoffs;
pub mod ste_dte;
pub mod stress;
