//! The one rule for the names of the files in a mesh folder
//! (`meshes/<scene>/`): `<member>_<blank>_<level>` for a body's mesh, its
//! report and the loaded side's stiffness file; `_<side>` appended for the
//! opposite side's stiffness file; `manifest.json` for the folder. Also
//! where `validate reference` writes each mesh level's results
//! ([`reference_dir`]), which the report and the studies read.

use geometry::design::Member;
use geometry::gear_body::Blank;
use geometry::generation::Side;
pub use geometry::scene::MeshLevel;
use std::path::{Path, PathBuf};

/// Where the reference of mesh level `level` writes its results:
/// `<out>/<scene>/reference/` for the reduced level (the meshes of the
/// reduced model), `<out>/<scene>/reference_<level>/` for a finer one.
pub fn reference_dir(out: &Path, scene: &str, level: &str) -> PathBuf {
    match level {
        "reduced" => out.join(scene).join("reference"),
        l => out.join(scene).join(format!("reference_{l}")),
    }
}

/// A body's files: `<member>_<blank>_<level>`.
pub fn mesh_stem(member: Member, blank: Blank, level: MeshLevel) -> String {
    stem_named(member, blank, level.name())
}

/// [`mesh_stem`] with the level given by its name, as the studies'
/// `--levels` options take it.
pub fn stem_named(member: Member, blank: Blank, level: &str) -> String {
    format!("{}_{}_{level}", member.name(), blank.name())
}

/// The stiffness file's stem for loads on the `side` flank: the mesh stem
/// for the scene's loaded side, `<mesh stem>_<side>` for the other one.
pub fn stiffness_stem(
    member: Member,
    blank: Blank,
    level: MeshLevel,
    side: Side,
    loaded: Side,
) -> String {
    let m = mesh_stem(member, blank, level);
    if side == loaded {
        m
    } else {
        format!("{m}_{}", side.name())
    }
}

/// `<dir>/<stem>.msh`.
pub fn msh(dir: &Path, stem: &str) -> PathBuf {
    dir.join(format!("{stem}.msh"))
}

/// `<dir>/<stem>.stiffness.h5`.
pub fn stiffness_h5(dir: &Path, stem: &str) -> PathBuf {
    dir.join(format!("{stem}.stiffness.h5"))
}

/// `<dir>/manifest.json`.
pub fn manifest(dir: &Path) -> PathBuf {
    dir.join("manifest.json")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stems_follow_member_blank_level_and_side() {
        assert_eq!(
            mesh_stem(Member::Wheel, Blank::Lightweight, MeshLevel::Reduced),
            "wheel_lightweight_reduced"
        );
        let s = stiffness_stem(
            Member::Pinion,
            Blank::Standard,
            MeshLevel::Reference,
            Side::Drive.other(),
            Side::Drive,
        );
        assert_eq!(
            s,
            format!("pinion_standard_reference_{}", Side::Drive.other().name())
        );
        for l in MeshLevel::FINEST_FIRST {
            assert_eq!(MeshLevel::from_name(l.name()), Some(l));
        }
        assert_eq!(MeshLevel::from_name("coarse"), None);
    }
}
