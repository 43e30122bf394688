//! Signal processing of run results: [`spectrum`] (short-time Fourier
//! transform and its spectrogram chart) and [`runup_orders`] (order
//! analysis of a run-up in the pinion's angle domain).

pub mod runup_orders;
pub mod spectrum;
