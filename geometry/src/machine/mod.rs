//! Face milling from machine settings: the flank a cradle-mounted head
//! cutter generates on a rolling work, and its normal deviation from the
//! design's conjugate flank.
//!
//! A design file may give, beside its design data, the machine settings
//! of each of the four flanks (`[machine_settings.<member>.<flank>]`,
//! [`settings`]). The flanks every later stage uses stay the design's
//! conjugate pair (the complementary crown-gear generation of
//! [`crate::generation`]); what the settings cut differently enters as a
//! measured-like topography of the pinion's ease-off ([`deviation`]): the
//! pinion's normal deviation plus the wheel's at the mating point, on a grid
//! of the pinion's normalised flank coordinates. Each member's deviation is
//! taken up to a rotation about its axis (the tooth's angular position,
//! which the settings fix only together with the indexing of the blank),
//! removed so that it vanishes at the mean point; the tooth thicknesses
//! stay those of the design data.
//!
//! The machine frame ([`kinematics`]) is the generating crown gear's frame
//! of [`crate::generation`]: origin at the machine centre, z the cradle
//! axis, the cradle plane z = 0, the pinion's work axis below it and the
//! wheel's above, both in the x–z plane at the machine root angle. These
//! are the toolkit's conventions (Litvin's, with its signs), not those of a
//! machine maker's summary; [`settings::MachineSettings::of_crown_generation`]
//! gives the settings that cut the design's own flanks.

pub mod deviation;
pub mod kinematics;
pub mod settings;
pub mod summary;
pub mod surface_fit;
pub mod synthesis;
