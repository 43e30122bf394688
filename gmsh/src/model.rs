//! `gmsh/model`: models, entities, physical groups, geometry queries.

use std::os::raw::c_int;

use gmsh_sys as sys;

use crate::ffi::{b, check, cstr, flatten, pairs, OutArray, OutStr};
use crate::{DimTag, Result, Session};

impl Session {
    /// Adds a new model and makes it the current one (`gmshModelAdd`).
    pub fn add_model(&self, name: &str) -> Result<()> {
        let name = cstr("model name", name)?;
        // SAFETY: valid C string.
        check("gmshModelAdd", |ierr| unsafe {
            sys::gmshModelAdd(name.as_ptr(), ierr)
        })
    }

    /// Makes the model `name` current (`gmshModelSetCurrent`).
    pub fn set_current(&self, name: &str) -> Result<()> {
        let name = cstr("model name", name)?;
        // SAFETY: valid C string.
        check("gmshModelSetCurrent", |ierr| unsafe {
            sys::gmshModelSetCurrent(name.as_ptr(), ierr)
        })
    }

    /// Clears all models and post-processing data and adds a new empty model
    /// (`gmshClear`).
    pub fn clear(&self) -> Result<()> {
        // SAFETY: no pointers besides ierr.
        check("gmshClear", |ierr| unsafe { sys::gmshClear(ierr) })
    }

    /// All entities of dimension `dim` of the current model, or of all
    /// dimensions if `dim < 0` (`gmshModelGetEntities`).
    pub fn get_entities(&self, dim: i32) -> Result<Vec<DimTag>> {
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid out-pointers; the array is freed by OutArray.
        check("gmshModelGetEntities", |ierr| unsafe {
            sys::gmshModelGetEntities(out.ptr(), out.len(), dim, ierr)
        })?;
        Ok(pairs(out.as_slice()))
    }

    /// The boundary of `dimtags` (`gmshModelGetBoundary`): `combined` gives
    /// the boundary of the combined entities, `oriented` signs the tags by
    /// orientation, `recursive` descends to points.
    pub fn get_boundary(
        &self,
        dimtags: &[DimTag],
        combined: bool,
        oriented: bool,
        recursive: bool,
    ) -> Result<Vec<DimTag>> {
        let flat = flatten(dimtags);
        let mut out = OutArray::<c_int>::new();
        // SAFETY: input slice and out-pointers are valid for the call.
        check("gmshModelGetBoundary", |ierr| unsafe {
            sys::gmshModelGetBoundary(
                flat.as_ptr(),
                flat.len(),
                out.ptr(),
                out.len(),
                b(combined),
                b(oriented),
                b(recursive),
                ierr,
            )
        })?;
        Ok(pairs(out.as_slice()))
    }

    /// The bounding box `[xmin, ymin, zmin, xmax, ymax, zmax]` of an entity,
    /// or of the whole model if `dim < 0` and `tag < 0`
    /// (`gmshModelGetBoundingBox`).
    pub fn get_bounding_box(&self, dim: i32, tag: i32) -> Result<[f64; 6]> {
        let mut bb = [0.0f64; 6];
        let [x0, y0, z0, x1, y1, z1] = &mut bb;
        // SAFETY: six valid out-pointers.
        check("gmshModelGetBoundingBox", |ierr| unsafe {
            sys::gmshModelGetBoundingBox(dim, tag, x0, y0, z0, x1, y1, z1, ierr)
        })?;
        Ok(bb)
    }

    /// Adds a physical group of dimension `dim` from the entities `tags`, with
    /// tag `tag` (automatic if `tag < 0`) and name `name` (none if empty);
    /// returns its tag (`gmshModelAddPhysicalGroup`).
    pub fn add_physical_group(&self, dim: i32, tags: &[i32], tag: i32, name: &str) -> Result<i32> {
        let name = cstr("physical group name", name)?;
        // SAFETY: valid slice and C string.
        check("gmshModelAddPhysicalGroup", |ierr| unsafe {
            sys::gmshModelAddPhysicalGroup(dim, tags.as_ptr(), tags.len(), tag, name.as_ptr(), ierr)
        })
    }

    /// Sets the name of the physical group `(dim, tag)`
    /// (`gmshModelSetPhysicalName`).
    pub fn set_physical_name(&self, dim: i32, tag: i32, name: &str) -> Result<()> {
        let name = cstr("physical group name", name)?;
        // SAFETY: valid C string.
        check("gmshModelSetPhysicalName", |ierr| unsafe {
            sys::gmshModelSetPhysicalName(dim, tag, name.as_ptr(), ierr)
        })
    }

    /// All physical groups of dimension `dim` (all dimensions if `dim < 0`)
    /// (`gmshModelGetPhysicalGroups`).
    pub fn get_physical_groups(&self, dim: i32) -> Result<Vec<DimTag>> {
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid out-pointers; the array is freed by OutArray.
        check("gmshModelGetPhysicalGroups", |ierr| unsafe {
            sys::gmshModelGetPhysicalGroups(out.ptr(), out.len(), dim, ierr)
        })?;
        Ok(pairs(out.as_slice()))
    }

    /// The entity tags of the physical group `(dim, tag)`
    /// (`gmshModelGetEntitiesForPhysicalGroup`).
    pub fn get_entities_for_physical_group(&self, dim: i32, tag: i32) -> Result<Vec<i32>> {
        let mut out = OutArray::<c_int>::new();
        // SAFETY: valid out-pointers; the array is freed by OutArray.
        check("gmshModelGetEntitiesForPhysicalGroup", |ierr| unsafe {
            sys::gmshModelGetEntitiesForPhysicalGroup(dim, tag, out.ptr(), out.len(), ierr)
        })?;
        Ok(out.to_vec())
    }

    /// Evaluates the parametrization of entity `(dim, tag)` at the parametric
    /// coordinates `params` (1 per point on curves, 2 on surfaces): returns
    /// `[x, y, z, ...]` (`gmshModelGetValue`).
    pub fn get_value(&self, dim: i32, tag: i32, params: &[f64]) -> Result<Vec<f64>> {
        let mut out = OutArray::<f64>::new();
        // SAFETY: valid slice and out-pointers.
        check("gmshModelGetValue", |ierr| unsafe {
            sys::gmshModelGetValue(
                dim,
                tag,
                params.as_ptr(),
                params.len(),
                out.ptr(),
                out.len(),
                ierr,
            )
        })?;
        Ok(out.to_vec())
    }

    /// Unit normals of surface `tag` at the parametric coordinates
    /// `[u, v, ...]`: returns `[nx, ny, nz, ...]` (`gmshModelGetNormal`).
    pub fn get_normal(&self, tag: i32, params: &[f64]) -> Result<Vec<f64>> {
        let mut out = OutArray::<f64>::new();
        // SAFETY: valid slice and out-pointers.
        check("gmshModelGetNormal", |ierr| unsafe {
            sys::gmshModelGetNormal(
                tag,
                params.as_ptr(),
                params.len(),
                out.ptr(),
                out.len(),
                ierr,
            )
        })?;
        Ok(out.to_vec())
    }

    /// The `(min, max)` parametric bounds of entity `(dim, tag)`, one value
    /// per parametric dimension (`gmshModelGetParametrizationBounds`).
    pub fn get_parametrization_bounds(&self, dim: i32, tag: i32) -> Result<(Vec<f64>, Vec<f64>)> {
        let mut min = OutArray::<f64>::new();
        let mut max = OutArray::<f64>::new();
        // SAFETY: valid out-pointers; arrays freed by OutArray.
        check("gmshModelGetParametrizationBounds", |ierr| unsafe {
            sys::gmshModelGetParametrizationBounds(
                dim,
                tag,
                min.ptr(),
                min.len(),
                max.ptr(),
                max.len(),
                ierr,
            )
        })?;
        Ok((min.to_vec(), max.to_vec()))
    }

    /// The closest points on entity `(dim, tag)` (curve or surface) to the
    /// points `coord = [x, y, z, ...]`: returns `(closest [x, y, z, ...],
    /// parametric coordinates)` (`gmshModelGetClosestPoint`).
    pub fn get_closest_point(
        &self,
        dim: i32,
        tag: i32,
        coord: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>)> {
        let mut closest = OutArray::<f64>::new();
        let mut param = OutArray::<f64>::new();
        // SAFETY: valid slice and out-pointers.
        check("gmshModelGetClosestPoint", |ierr| unsafe {
            sys::gmshModelGetClosestPoint(
                dim,
                tag,
                coord.as_ptr(),
                coord.len(),
                closest.ptr(),
                closest.len(),
                param.ptr(),
                param.len(),
                ierr,
            )
        })?;
        Ok((closest.to_vec(), param.to_vec()))
    }

    /// The name of physical group `(dim, tag)` (`gmshModelGetPhysicalName`).
    pub fn get_physical_name(&self, dim: i32, tag: i32) -> Result<String> {
        let mut out = OutStr::new();
        // SAFETY: valid out-pointer; the string is freed by OutStr.
        check("gmshModelGetPhysicalName", |ierr| unsafe {
            sys::gmshModelGetPhysicalName(dim, tag, out.ptr(), ierr)
        })?;
        Ok(out.to_string())
    }

    /// The type of entity `(dim, tag)`, e.g. `"Plane"`, `"Cylinder"`,
    /// `"BSpline surface"` (`gmshModelGetType`).
    pub fn get_type(&self, dim: i32, tag: i32) -> Result<String> {
        let mut out = OutStr::new();
        // SAFETY: valid out-pointer; the string is freed by OutStr.
        check("gmshModelGetType", |ierr| unsafe {
            sys::gmshModelGetType(dim, tag, out.ptr(), ierr)
        })?;
        Ok(out.to_string())
    }

    /// The `(upward, downward)` adjacent entity tags of `(dim, tag)`: entities
    /// of dimension `dim + 1` and `dim - 1` (`gmshModelGetAdjacencies`).
    pub fn get_adjacencies(&self, dim: i32, tag: i32) -> Result<(Vec<i32>, Vec<i32>)> {
        let mut up = OutArray::<c_int>::new();
        let mut down = OutArray::<c_int>::new();
        // SAFETY: valid out-pointers; arrays freed by OutArray.
        check("gmshModelGetAdjacencies", |ierr| unsafe {
            sys::gmshModelGetAdjacencies(dim, tag, up.ptr(), up.len(), down.ptr(), down.len(), ierr)
        })?;
        Ok((up.to_vec(), down.to_vec()))
    }
}
