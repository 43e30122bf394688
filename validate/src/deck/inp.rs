//! Writes a [`Deck`] as a CalculiX / Abaqus input file (`.inp`), SI units
//! (m, N, Pa). Numbers carry 13 significant digits: CalculiX reads at most
//! 20 characters per field. Node and element numbers start at 1: the pinion's first,
//! then the wheel's, then the rigid body's reference and rotation nodes.

use super::{Deck, DeckContact};
use std::fmt::Write as _;

/// Node numbers of the rigid body's reference and rotation nodes.
pub fn rigid_nodes(deck: &Deck) -> (usize, usize) {
    let n = deck.bodies[0].nodes.len() + deck.bodies[1].nodes.len();
    (n + 1, n + 2)
}

/// Clearance factor c₀ of CalculiX's linear node-to-surface law: springs
/// are made for slave nodes within c₀ · √(node area) of the master, here
/// about 0.1 mm on millimetre faces, beyond any closure of the solve.
pub const CLEARANCE_FACTOR: f64 = 0.1;

/// Tension σ∞ that CalculiX's linear node-to-surface law allows at large
/// clearances, Pa: small enough that open springs carry nothing worth
/// counting (1 Pa on a square millimetre is 1 µN).
pub const TENSION_PA: f64 = 1.0;

/// The deck's text.
pub fn write(deck: &Deck) -> String {
    let mut s = String::new();
    let [p, w] = &deck.bodies;
    let (np, ep) = (p.nodes.len(), p.elements.len());
    let (nref, nrot) = rigid_nodes(deck);
    let _ = writeln!(
        s,
        "** Reference FE of scene {} at position {} (pinion angle {:.9} deg), mesh level {}.",
        deck.scene,
        deck.position,
        deck.phi.to_degrees(),
        deck.level.name()
    );
    let _ = writeln!(
        s,
        "** Written by `validate export-inp`. SI units: m, N, Pa."
    );
    let _ = writeln!(
        s,
        "** Pinion frame: the pinion axis is z through the origin."
    );
    for (name, b) in [("pinion", p), ("wheel", w)] {
        let _ = writeln!(
            s,
            "** {name} mesh {} sha256 {}",
            b.mesh.display(),
            b.mesh_sha256
        );
    }
    let _ = writeln!(
        s,
        "** Loaded TE of a step = {:.12e} x U3 of node {nrot} (rad; z1/z2 x driving sense).",
        deck.ratio * deck.direction
    );
    let _ = writeln!(
        s,
        "*HEADING\nscene {} position {} contact {}",
        deck.scene,
        deck.position,
        deck.contact.name()
    );
    s.push_str("*NODE, NSET=NPINION\n");
    nodes(&mut s, &p.nodes, 0);
    s.push_str("*NODE, NSET=NWHEEL\n");
    nodes(&mut s, &w.nodes, np);
    let _ = writeln!(s, "*NODE, NSET=NREF\n{nref}, 0., 0., 0.");
    let _ = writeln!(s, "*NODE, NSET=NROT\n{nrot}, 0., 0., 0.");
    s.push_str("*ELEMENT, TYPE=C3D10, ELSET=EPINION\n");
    elements(&mut s, &p.elements, 0, 0);
    s.push_str("*ELEMENT, TYPE=C3D10, ELSET=EWHEEL\n");
    elements(&mut s, &w.elements, ep, np);
    set(&mut s, "PBORE", p.bore.iter().map(|&i| i + 1));
    set(&mut s, "WBORE", w.bore.iter().map(|&i| i + 1 + np));
    s.push_str("*SURFACE, NAME=PFLANK, TYPE=ELEMENT\n");
    for &(e, label) in &p.flank {
        let _ = writeln!(s, "{}, S{label}", e + 1);
    }
    s.push_str("*SURFACE, NAME=WFLANK, TYPE=ELEMENT\n");
    for &(e, label) in &w.flank {
        let _ = writeln!(s, "{}, S{label}", e + 1 + ep);
    }
    for (name, b) in [("PINION", p), ("WHEEL", w)] {
        let _ = writeln!(
            s,
            "*MATERIAL, NAME={name}_MATERIAL\n*ELASTIC\n{:.12e}, {:.12e}\n*SOLID SECTION, ELSET=E{name}, MATERIAL={name}_MATERIAL",
            b.youngs_modulus_pa, b.poisson_ratio
        );
    }
    let _ = writeln!(
        s,
        "*RIGID BODY, NSET=PBORE, REF NODE={nref}, ROT NODE={nrot}"
    );
    match deck.contact {
        DeckContact::None => {}
        c => {
            s.push_str("*SURFACE INTERACTION, NAME=FLANKS\n");
            s.push_str("*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n");
            if c == DeckContact::NodeToSurface {
                let _ = writeln!(
                    s,
                    "{:.12e}, {TENSION_PA:e}, {CLEARANCE_FACTOR:e}",
                    deck.penalty_slope
                );
            } else {
                let _ = writeln!(s, "{:.12e}", deck.penalty_slope);
            }
            let _ = writeln!(
                s,
                "*CONTACT PAIR, INTERACTION=FLANKS, TYPE={}\nPFLANK, WFLANK",
                if c == DeckContact::NodeToSurface {
                    "NODE TO SURFACE"
                } else {
                    "SURFACE TO SURFACE"
                }
            );
        }
    }
    let held = format!("WBORE, 1, 3\n{nref}, 1, 3\n{nrot}, 1, 2\n");
    let print = "*NODE PRINT, NSET=NROT\nU\n*NODE PRINT, NSET=NROT\nRF\n*NODE PRINT, NSET=WBORE, TOTALS=ONLY\nRF\n";
    // Step 1: the pinion turned to its first overlap.
    let _ = writeln!(
        s,
        "** Step 1: the pinion turned by {:.9e} rad about z (its first flank node overlaps the wheel).",
        deck.start_rotation
    );
    let _ = write!(
        s,
        "*STEP, INC=200\n*STATIC\n1., 1.\n*BOUNDARY\n{held}{nrot}, 3, 3, {:.12e}\n{print}*END STEP\n",
        deck.start_rotation
    );
    if deck.contact != DeckContact::None {
        for (k, t) in deck.torques_nm.iter().enumerate() {
            let _ = writeln!(
                s,
                "** Step {}: pinion torque {t} N m, the rotation free.",
                k + 2
            );
            let _ = write!(
                s,
                "*STEP, INC=200\n*STATIC\n1., 1.\n*BOUNDARY, OP=NEW\n{held}*CLOAD, OP=NEW\n{nrot}, 3, {:.12e}\n{print}*END STEP\n",
                deck.direction * t
            );
        }
    }
    s
}

fn nodes(s: &mut String, x: &[[f64; 3]], offset: usize) {
    for (i, p) in x.iter().enumerate() {
        let _ = writeln!(
            s,
            "{}, {:.12e}, {:.12e}, {:.12e}",
            i + 1 + offset,
            p[0],
            p[1],
            p[2]
        );
    }
}

fn elements(s: &mut String, e: &[[usize; 10]], offset: usize, node_offset: usize) {
    for (k, el) in e.iter().enumerate() {
        let _ = write!(s, "{}", k + 1 + offset);
        for &n in el {
            let _ = write!(s, ", {}", n + 1 + node_offset);
        }
        s.push('\n');
    }
}

/// A node set, 16 numbers per line (the format's limit).
fn set(s: &mut String, name: &str, ids: impl Iterator<Item = usize>) {
    let _ = writeln!(s, "*NSET, NSET={name}");
    let ids: Vec<usize> = ids.collect();
    for chunk in ids.chunks(16) {
        let line: Vec<String> = chunk.iter().map(|i| i.to_string()).collect();
        let _ = writeln!(s, "{},", line.join(", "));
    }
}
