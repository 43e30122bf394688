//! Signal processing of run results: [`spectrum`] (short-time Fourier
//! transform and its spectrogram chart), [`runup_orders`] (order
//! analysis of a run-up in the pinion's angle domain) and
//! [`angle_domain`] (two runs compared at the same pinion rotations).

pub mod angle_domain;
pub mod runup_orders;
pub mod spectrum;
