//! `gmsh/model/occ`: the OpenCASCADE CAD kernel. Entities created here are
//! visible to the model (queries, meshing) only after [`Session::occ_synchronize`].
//! Tags are chosen automatically (`tag = -1`) unless an argument says otherwise.

use std::f64::consts::PI;
use std::os::raw::c_int;

use gmsh_sys as sys;

use crate::ffi::{b, check, cstr, flatten, pairs, OutArray, OutNested};
use crate::{BooleanResult, DimTag, Result, Session};

/// Signature shared by the four OCC boolean operations.
type BooleanFn = unsafe extern "C" fn(
    *const c_int,
    usize,
    *const c_int,
    usize,
    *mut *mut c_int,
    *mut usize,
    *mut *mut *mut c_int,
    *mut *mut usize,
    *mut usize,
    c_int,
    c_int,
    c_int,
    *mut c_int,
);

impl Session {
    /// Adds a point; `mesh_size` is the target mesh size there (`0` = none),
    /// `tag < 0` chooses the tag (`gmshModelOccAddPoint`). Returns its tag.
    pub fn occ_add_point(&self, x: f64, y: f64, z: f64, mesh_size: f64, tag: i32) -> Result<i32> {
        // SAFETY: scalar arguments only.
        check("gmshModelOccAddPoint", |ierr| unsafe {
            sys::gmshModelOccAddPoint(x, y, z, mesh_size, tag, ierr)
        })
    }

    /// Adds a straight line between the points `a` and `b`
    /// (`gmshModelOccAddLine`). Returns its tag.
    pub fn occ_add_line(&self, a: i32, b: i32) -> Result<i32> {
        // SAFETY: scalar arguments only.
        check("gmshModelOccAddLine", |ierr| unsafe {
            sys::gmshModelOccAddLine(a, b, -1, ierr)
        })
    }

    /// Adds a circle arc from point `start` to point `end` around the center
    /// point `center` (`gmshModelOccAddCircleArc` with `center = 1`; in gmsh
    /// 4.15 the middle point may also be a point on the arc). Returns its tag.
    pub fn occ_add_circle_arc(&self, start: i32, center: i32, end: i32) -> Result<i32> {
        // SAFETY: scalar arguments only.
        check("gmshModelOccAddCircleArc", |ierr| unsafe {
            sys::gmshModelOccAddCircleArc(start, center, end, -1, 1, ierr)
        })
    }

    /// Adds a spline (C2 B-spline) interpolating the points `point_tags`, with
    /// no imposed tangents (`gmshModelOccAddSpline`); if the first and last
    /// tags are equal the curve is periodic. Returns its tag.
    pub fn occ_add_spline(&self, point_tags: &[i32]) -> Result<i32> {
        // SAFETY: valid slice; no tangents.
        check("gmshModelOccAddSpline", |ierr| unsafe {
            sys::gmshModelOccAddSpline(
                point_tags.as_ptr(),
                point_tags.len(),
                -1,
                std::ptr::null(),
                0,
                ierr,
            )
        })
    }

    /// Adds a B-spline of degree `degree` with control points `point_tags`
    /// (uniform weights, default knots) (`gmshModelOccAddBSpline`). Returns
    /// its tag.
    pub fn occ_add_bspline(&self, point_tags: &[i32], degree: i32) -> Result<i32> {
        // SAFETY: valid slice; empty weights/knots/multiplicities.
        check("gmshModelOccAddBSpline", |ierr| unsafe {
            sys::gmshModelOccAddBSpline(
                point_tags.as_ptr(),
                point_tags.len(),
                -1,
                degree,
                std::ptr::null(),
                0,
                std::ptr::null(),
                0,
                std::ptr::null(),
                0,
                ierr,
            )
        })
    }

    /// Adds a curve loop (a closed wire) from the curves `curve_tags`
    /// (`gmshModelOccAddCurveLoop`). Returns its tag.
    pub fn occ_add_curve_loop(&self, curve_tags: &[i32]) -> Result<i32> {
        // SAFETY: valid slice.
        check("gmshModelOccAddCurveLoop", |ierr| unsafe {
            sys::gmshModelOccAddCurveLoop(curve_tags.as_ptr(), curve_tags.len(), -1, ierr)
        })
    }

    /// Adds a wire (open or closed) from the curves `curve_tags`; with
    /// `check_closed` it must be closed (`gmshModelOccAddWire`). Returns its
    /// tag.
    pub fn occ_add_wire(&self, curve_tags: &[i32], check_closed: bool) -> Result<i32> {
        // SAFETY: valid slice.
        check("gmshModelOccAddWire", |ierr| unsafe {
            sys::gmshModelOccAddWire(
                curve_tags.as_ptr(),
                curve_tags.len(),
                -1,
                b(check_closed),
                ierr,
            )
        })
    }

    /// Adds a plane surface bounded by the curve loops `loops` (first the
    /// outer one, then holes) (`gmshModelOccAddPlaneSurface`). Returns its tag.
    pub fn occ_add_plane_surface(&self, loops: &[i32]) -> Result<i32> {
        // SAFETY: valid slice.
        check("gmshModelOccAddPlaneSurface", |ierr| unsafe {
            sys::gmshModelOccAddPlaneSurface(loops.as_ptr(), loops.len(), -1, ierr)
        })
    }

    /// Adds a surface filling the curve loop `wire`
    /// (`gmshModelOccAddSurfaceFilling`, gmsh's defaults: no constraint
    /// points, degree 2, 15 points on curves, 2 iterations, not anisotropic,
    /// tolerances 1e-5 / 1e-4 / 1e-2 / 0.1, max degree 8, max 9 segments).
    /// Returns its tag.
    pub fn occ_add_surface_filling(&self, wire: i32) -> Result<i32> {
        // SAFETY: empty point list; scalar arguments.
        check("gmshModelOccAddSurfaceFilling", |ierr| unsafe {
            sys::gmshModelOccAddSurfaceFilling(
                wire,
                -1,
                std::ptr::null(),
                0,
                2,
                15,
                2,
                0,
                1e-5,
                1e-4,
                1e-2,
                0.1,
                8,
                9,
                ierr,
            )
        })
    }

    /// Adds a surface (or a solid with `make_solid`) through the wires
    /// `wire_tags` (`gmshModelOccAddThruSections`). `make_ruled` forces ruled
    /// surfaces, `max_degree` bounds the degree (`-1` = default),
    /// `continuity` is `""` (default), `"C0"`, `"G1"`, `"C1"`, `"G2"`, `"C2"`,
    /// `"C3"` or `"CN"`, `parametrization` is `""` (default),
    /// `"ChordLength"`, `"Centripetal"` or `"IsoParametric"`, and `smoothing`
    /// enables smoothing. Returns the created entities.
    #[allow(clippy::too_many_arguments)]
    pub fn occ_add_thru_sections(
        &self,
        wire_tags: &[i32],
        make_solid: bool,
        make_ruled: bool,
        max_degree: i32,
        continuity: &str,
        parametrization: &str,
        smoothing: bool,
    ) -> Result<Vec<DimTag>> {
        let continuity = cstr("continuity", continuity)?;
        let parametrization = cstr("parametrization", parametrization)?;
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid slice, C strings and out-pointers.
        check("gmshModelOccAddThruSections", |ierr| unsafe {
            sys::gmshModelOccAddThruSections(
                wire_tags.as_ptr(),
                wire_tags.len(),
                out.ptr(),
                out.len(),
                -1,
                b(make_solid),
                b(make_ruled),
                max_degree,
                continuity.as_ptr(),
                parametrization.as_ptr(),
                b(smoothing),
                ierr,
            )
        })?;
        Ok(pairs(out.as_slice()))
    }

    /// Adds a full cylinder with base center `(x, y, z)`, axis `(dx, dy, dz)`
    /// (its length is the height) and radius `r` (`gmshModelOccAddCylinder`,
    /// angle 2π). Returns the volume tag.
    #[allow(clippy::too_many_arguments)]
    pub fn occ_add_cylinder(
        &self,
        x: f64,
        y: f64,
        z: f64,
        dx: f64,
        dy: f64,
        dz: f64,
        r: f64,
    ) -> Result<i32> {
        // SAFETY: scalar arguments only.
        check("gmshModelOccAddCylinder", |ierr| unsafe {
            sys::gmshModelOccAddCylinder(x, y, z, dx, dy, dz, r, -1, 2.0 * PI, ierr)
        })
    }

    /// Adds a box with corner `(x, y, z)` and extents `(dx, dy, dz)`
    /// (`gmshModelOccAddBox`). Returns the volume tag.
    pub fn occ_add_box(&self, x: f64, y: f64, z: f64, dx: f64, dy: f64, dz: f64) -> Result<i32> {
        // SAFETY: scalar arguments only.
        check("gmshModelOccAddBox", |ierr| unsafe {
            sys::gmshModelOccAddBox(x, y, z, dx, dy, dz, -1, ierr)
        })
    }

    /// Adds a full cone (frustum) with base center `(x, y, z)`, axis
    /// `(dx, dy, dz)`, base radius `r1` and top radius `r2`
    /// (`gmshModelOccAddCone`, angle 2π). Returns the volume tag.
    #[allow(clippy::too_many_arguments)]
    pub fn occ_add_cone(
        &self,
        x: f64,
        y: f64,
        z: f64,
        dx: f64,
        dy: f64,
        dz: f64,
        r1: f64,
        r2: f64,
    ) -> Result<i32> {
        // SAFETY: scalar arguments only.
        check("gmshModelOccAddCone", |ierr| unsafe {
            sys::gmshModelOccAddCone(x, y, z, dx, dy, dz, r1, r2, -1, 2.0 * PI, ierr)
        })
    }

    /// Revolves `dimtags` by `angle` (radians) around the axis through
    /// `(x, y, z)` with direction `(ax, ay, az)` (`gmshModelOccRevolve`, no
    /// structured layers). Returns the created entities: for each input,
    /// the "top" entity, then the swept one, then the lateral ones.
    #[allow(clippy::too_many_arguments)]
    pub fn occ_revolve(
        &self,
        dimtags: &[DimTag],
        x: f64,
        y: f64,
        z: f64,
        ax: f64,
        ay: f64,
        az: f64,
        angle: f64,
    ) -> Result<Vec<DimTag>> {
        let flat = flatten(dimtags);
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid slice and out-pointers; empty layer arrays.
        check("gmshModelOccRevolve", |ierr| unsafe {
            sys::gmshModelOccRevolve(
                flat.as_ptr(),
                flat.len(),
                x,
                y,
                z,
                ax,
                ay,
                az,
                angle,
                out.ptr(),
                out.len(),
                std::ptr::null(),
                0,
                std::ptr::null(),
                0,
                0,
                ierr,
            )
        })?;
        Ok(pairs(out.as_slice()))
    }

    /// Extrudes `dimtags` by the vector `(dx, dy, dz)` (`gmshModelOccExtrude`,
    /// no structured layers). Returns the created entities (top, swept,
    /// lateral for each input).
    pub fn occ_extrude(
        &self,
        dimtags: &[DimTag],
        dx: f64,
        dy: f64,
        dz: f64,
    ) -> Result<Vec<DimTag>> {
        let flat = flatten(dimtags);
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid slice and out-pointers; empty layer arrays.
        check("gmshModelOccExtrude", |ierr| unsafe {
            sys::gmshModelOccExtrude(
                flat.as_ptr(),
                flat.len(),
                dx,
                dy,
                dz,
                out.ptr(),
                out.len(),
                std::ptr::null(),
                0,
                std::ptr::null(),
                0,
                0,
                ierr,
            )
        })?;
        Ok(pairs(out.as_slice()))
    }

    /// Rotates `dimtags` in place by `angle` (radians) around the axis through
    /// `(x, y, z)` with direction `(ax, ay, az)` (`gmshModelOccRotate`).
    #[allow(clippy::too_many_arguments)]
    pub fn occ_rotate(
        &self,
        dimtags: &[DimTag],
        x: f64,
        y: f64,
        z: f64,
        ax: f64,
        ay: f64,
        az: f64,
        angle: f64,
    ) -> Result<()> {
        let flat = flatten(dimtags);
        // SAFETY: valid slice.
        check("gmshModelOccRotate", |ierr| unsafe {
            sys::gmshModelOccRotate(flat.as_ptr(), flat.len(), x, y, z, ax, ay, az, angle, ierr)
        })
    }

    /// Copies `dimtags` (`gmshModelOccCopy`). Returns the new entities.
    pub fn occ_copy(&self, dimtags: &[DimTag]) -> Result<Vec<DimTag>> {
        let flat = flatten(dimtags);
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid slice and out-pointers.
        check("gmshModelOccCopy", |ierr| unsafe {
            sys::gmshModelOccCopy(flat.as_ptr(), flat.len(), out.ptr(), out.len(), ierr)
        })?;
        Ok(pairs(out.as_slice()))
    }

    fn occ_boolean(
        &self,
        call: &'static str,
        f: BooleanFn,
        object: &[DimTag],
        tool: &[DimTag],
        remove_object: bool,
        remove_tool: bool,
    ) -> Result<BooleanResult> {
        let obj = flatten(object);
        let tl = flatten(tool);
        let mut out = OutArray::<c_int>::new();
        let mut map = OutNested::<c_int>::new();
        // SAFETY: valid slices and out-pointers; all gmsh-allocated arrays
        // are freed by OutArray / OutNested.
        check(call, |ierr| unsafe {
            f(
                obj.as_ptr(),
                obj.len(),
                tl.as_ptr(),
                tl.len(),
                out.ptr(),
                out.len(),
                map.ptr(),
                map.lens(),
                map.n(),
                -1,
                b(remove_object),
                b(remove_tool),
                ierr,
            )
        })?;
        let map = map.to_vecs().iter().map(|v| pairs(v)).collect();
        Ok((pairs(out.as_slice()), map))
    }

    /// Boolean difference `object - tool` (`gmshModelOccCut`). Returns the
    /// resulting entities and, for each input (objects then tools), what it
    /// became.
    pub fn occ_cut(
        &self,
        object: &[DimTag],
        tool: &[DimTag],
        remove_object: bool,
        remove_tool: bool,
    ) -> Result<BooleanResult> {
        self.occ_boolean(
            "gmshModelOccCut",
            sys::gmshModelOccCut,
            object,
            tool,
            remove_object,
            remove_tool,
        )
    }

    /// Boolean union (`gmshModelOccFuse`); result as for [`Session::occ_cut`].
    pub fn occ_fuse(
        &self,
        object: &[DimTag],
        tool: &[DimTag],
        remove_object: bool,
        remove_tool: bool,
    ) -> Result<BooleanResult> {
        self.occ_boolean(
            "gmshModelOccFuse",
            sys::gmshModelOccFuse,
            object,
            tool,
            remove_object,
            remove_tool,
        )
    }

    /// Boolean fragments: all pieces, conformal at the interfaces
    /// (`gmshModelOccFragment`); result as for [`Session::occ_cut`].
    pub fn occ_fragment(
        &self,
        object: &[DimTag],
        tool: &[DimTag],
        remove_object: bool,
        remove_tool: bool,
    ) -> Result<BooleanResult> {
        self.occ_boolean(
            "gmshModelOccFragment",
            sys::gmshModelOccFragment,
            object,
            tool,
            remove_object,
            remove_tool,
        )
    }

    /// Boolean intersection (`gmshModelOccIntersect`); result as for
    /// [`Session::occ_cut`].
    pub fn occ_intersect(
        &self,
        object: &[DimTag],
        tool: &[DimTag],
        remove_object: bool,
        remove_tool: bool,
    ) -> Result<BooleanResult> {
        self.occ_boolean(
            "gmshModelOccIntersect",
            sys::gmshModelOccIntersect,
            object,
            tool,
            remove_object,
            remove_tool,
        )
    }

    /// Removes `dimtags`, with `recursive` also their boundaries
    /// (`gmshModelOccRemove`).
    pub fn occ_remove(&self, dimtags: &[DimTag], recursive: bool) -> Result<()> {
        let flat = flatten(dimtags);
        // SAFETY: valid slice.
        check("gmshModelOccRemove", |ierr| unsafe {
            sys::gmshModelOccRemove(flat.as_ptr(), flat.len(), b(recursive), ierr)
        })
    }

    /// Heals `dimtags` (all entities if empty) with gmsh's defaults:
    /// tolerance 1e-8, fix degenerated edges, small edges and small faces,
    /// sew faces, make solids (`gmshModelOccHealShapes`). Returns the healed
    /// entities.
    pub fn occ_heal_shapes(&self, dimtags: &[DimTag]) -> Result<Vec<DimTag>> {
        let flat = flatten(dimtags);
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid slice and out-pointers.
        check("gmshModelOccHealShapes", |ierr| unsafe {
            sys::gmshModelOccHealShapes(
                out.ptr(),
                out.len(),
                flat.as_ptr(),
                flat.len(),
                1e-8,
                1,
                1,
                1,
                1,
                1,
                ierr,
            )
        })?;
        Ok(pairs(out.as_slice()))
    }

    /// Synchronizes the OCC CAD representation with the gmsh model
    /// (`gmshModelOccSynchronize`); needed before model queries and meshing.
    pub fn occ_synchronize(&self) -> Result<()> {
        // SAFETY: no pointers besides ierr.
        check("gmshModelOccSynchronize", |ierr| unsafe {
            sys::gmshModelOccSynchronize(ierr)
        })
    }

    /// The mass (length, area or volume) of the OCC entity `(dim, tag)`
    /// (`gmshModelOccGetMass`).
    pub fn occ_get_mass(&self, dim: i32, tag: i32) -> Result<f64> {
        let mut mass = 0.0;
        // SAFETY: valid out-pointer.
        check("gmshModelOccGetMass", |ierr| unsafe {
            sys::gmshModelOccGetMass(dim, tag, &mut mass, ierr)
        })?;
        Ok(mass)
    }

    /// The center of mass of the OCC entity `(dim, tag)`
    /// (`gmshModelOccGetCenterOfMass`).
    pub fn occ_get_center_of_mass(&self, dim: i32, tag: i32) -> Result<[f64; 3]> {
        let mut c = [0.0f64; 3];
        let [x, y, z] = &mut c;
        // SAFETY: valid out-pointers.
        check("gmshModelOccGetCenterOfMass", |ierr| unsafe {
            sys::gmshModelOccGetCenterOfMass(dim, tag, x, y, z, ierr)
        })?;
        Ok(c)
    }

    /// All OCC entities of dimension `dim` (all dimensions if `dim < 0`),
    /// whether synchronized or not (`gmshModelOccGetEntities`).
    pub fn occ_get_entities(&self, dim: i32) -> Result<Vec<DimTag>> {
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid out-pointers; array freed by OutArray.
        check("gmshModelOccGetEntities", |ierr| unsafe {
            sys::gmshModelOccGetEntities(out.ptr(), out.len(), dim, ierr)
        })?;
        Ok(pairs(out.as_slice()))
    }
}
