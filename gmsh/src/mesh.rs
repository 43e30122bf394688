//! `gmsh/model/mesh` and `gmsh/model/mesh/field`.

use std::os::raw::c_int;

use gmsh_sys as sys;

use crate::ffi::{b, check, cstr, flatten, OutArray, OutNested};
use crate::{DimTag, MeshElements, Result, Session};

impl Session {
    /// Generates the mesh of the current model up to dimension `dim`
    /// (`gmshModelMeshGenerate`).
    pub fn mesh_generate(&self, dim: i32) -> Result<()> {
        // SAFETY: scalar arguments only.
        check("gmshModelMeshGenerate", |ierr| unsafe {
            sys::gmshModelMeshGenerate(dim, ierr)
        })
    }

    /// Sets the element order of the mesh (`2` for quadratic elements, e.g.
    /// tet10 = type 11), converting an existing mesh (`gmshModelMeshSetOrder`).
    pub fn mesh_set_order(&self, order: i32) -> Result<()> {
        // SAFETY: scalar arguments only.
        check("gmshModelMeshSetOrder", |ierr| unsafe {
            sys::gmshModelMeshSetOrder(order, ierr)
        })
    }

    /// Optimizes the whole mesh with `method` (`""` = default tetrahedral
    /// optimizer, `"Netgen"`, `"HighOrder"`, `"HighOrderElastic"`,
    /// `"HighOrderFastCurving"`, `"Laplace2D"`, `"Relocate2D"`,
    /// `"Relocate3D"`, `"QuadQuasiStructured"`, `"UntangleMeshGeometry"`),
    /// `force` applies it also to discrete entities, `niter` iterations
    /// (`gmshModelMeshOptimize`, all entities).
    pub fn mesh_optimize(&self, method: &str, force: bool, niter: i32) -> Result<()> {
        let method = cstr("method", method)?;
        // SAFETY: valid C string; empty dimTags.
        check("gmshModelMeshOptimize", |ierr| unsafe {
            sys::gmshModelMeshOptimize(method.as_ptr(), b(force), niter, std::ptr::null(), 0, ierr)
        })
    }

    /// Sets the target mesh size at the points `dimtags` (dimension 0 entities)
    /// (`gmshModelMeshSetSize`).
    pub fn mesh_set_size(&self, dimtags: &[DimTag], size: f64) -> Result<()> {
        let flat = flatten(dimtags);
        // SAFETY: valid slice.
        check("gmshModelMeshSetSize", |ierr| unsafe {
            sys::gmshModelMeshSetSize(flat.as_ptr(), flat.len(), size, ierr)
        })
    }

    /// Makes curve `tag` transfinite with `n_points` nodes (including its end
    /// points), distributed by `mesh_type` (`"Progression"`, `"Bump"` or
    /// `"Beta"`) with coefficient `coef` (`1.0` = uniform)
    /// (`gmshModelMeshSetTransfiniteCurve`).
    pub fn mesh_set_transfinite_curve(
        &self,
        tag: i32,
        n_points: i32,
        mesh_type: &str,
        coef: f64,
    ) -> Result<()> {
        let mesh_type = cstr("mesh type", mesh_type)?;
        // SAFETY: valid C string.
        check("gmshModelMeshSetTransfiniteCurve", |ierr| unsafe {
            sys::gmshModelMeshSetTransfiniteCurve(tag, n_points, mesh_type.as_ptr(), coef, ierr)
        })
    }

    /// Makes surface `tag` transfinite (`gmshModelMeshSetTransfiniteSurface`);
    /// `arrangement` of the triangles is `"Left"`, `"Right"`,
    /// `"AlternateLeft"`, `"AlternateRight"` or `"Alternate"`, `corner_tags`
    /// (3 or 4 points, or empty for automatic) are the corners.
    pub fn mesh_set_transfinite_surface(
        &self,
        tag: i32,
        arrangement: &str,
        corner_tags: &[i32],
    ) -> Result<()> {
        let arrangement = cstr("arrangement", arrangement)?;
        // SAFETY: valid C string and slice.
        check("gmshModelMeshSetTransfiniteSurface", |ierr| unsafe {
            sys::gmshModelMeshSetTransfiniteSurface(
                tag,
                arrangement.as_ptr(),
                corner_tags.as_ptr(),
                corner_tags.len(),
                ierr,
            )
        })
    }

    /// Asks for recombination of the triangles of surface `(dim, tag)` into
    /// quadrangles; `angle` is the threshold for the simple-recombination
    /// algorithm (gmsh's default is 45 degrees) (`gmshModelMeshSetRecombine`).
    pub fn mesh_set_recombine(&self, dim: i32, tag: i32, angle: f64) -> Result<()> {
        // SAFETY: scalar arguments only.
        check("gmshModelMeshSetRecombine", |ierr| unsafe {
            sys::gmshModelMeshSetRecombine(dim, tag, angle, ierr)
        })
    }

    /// The mesh nodes of entity `(dim, tag)` (all entities if `dim < 0` and
    /// `tag < 0`; with `include_boundary` also the nodes on its boundary):
    /// returns `(node tags, [x, y, z, ...], parametric coordinates)`, the last
    /// one filled only with `return_parametric` on curves and surfaces
    /// (`gmshModelMeshGetNodes`).
    pub fn mesh_get_nodes(
        &self,
        dim: i32,
        tag: i32,
        include_boundary: bool,
        return_parametric: bool,
    ) -> Result<(Vec<usize>, Vec<f64>, Vec<f64>)> {
        let mut tags = OutArray::<usize>::new();
        let mut coord = OutArray::<f64>::new();
        let mut param = OutArray::<f64>::new();
        // SAFETY: valid out-pointers; arrays freed by OutArray.
        check("gmshModelMeshGetNodes", |ierr| unsafe {
            sys::gmshModelMeshGetNodes(
                tags.ptr(),
                tags.len(),
                coord.ptr(),
                coord.len(),
                param.ptr(),
                param.len(),
                dim,
                tag,
                b(include_boundary),
                b(return_parametric),
                ierr,
            )
        })?;
        Ok((tags.to_vec(), coord.to_vec(), param.to_vec()))
    }

    /// The mesh elements of entity `(dim, tag)` (all if `dim < 0`, `tag < 0`):
    /// returns `(element types, element tags per type, node tags per type)`,
    /// the node tags of each type concatenated element by element
    /// (`gmshModelMeshGetElements`). Types follow the MSH numbering: 1 line2,
    /// 2 tri3, 4 tet4, 8 line3, 9 tri6, 11 tet10, 15 point.
    pub fn mesh_get_elements(&self, dim: i32, tag: i32) -> Result<MeshElements> {
        let mut types = OutArray::<c_int>::new();
        let mut elems = OutNested::<usize>::new();
        let mut nodes = OutNested::<usize>::new();
        // SAFETY: valid out-pointers; arrays freed by OutArray / OutNested.
        check("gmshModelMeshGetElements", |ierr| unsafe {
            sys::gmshModelMeshGetElements(
                types.ptr(),
                types.len(),
                elems.ptr(),
                elems.lens(),
                elems.n(),
                nodes.ptr(),
                nodes.lens(),
                nodes.n(),
                dim,
                tag,
                ierr,
            )
        })?;
        Ok((types.to_vec(), elems.to_vecs(), nodes.to_vecs()))
    }

    /// The quality `quality_name` (`"minSICN"`, `"minDetJac"`, `"maxDetJac"`,
    /// `"minSJ"`, `"minSIGE"`, `"gamma"`, `"innerRadius"`, `"outerRadius"`,
    /// `"minIsotropy"`, `"angleShape"`, `"minEdge"`, `"maxEdge"`, `"volume"`)
    /// of each element of `element_tags` (`gmshModelMeshGetElementQualities`,
    /// single task).
    pub fn mesh_get_element_qualities(
        &self,
        element_tags: &[usize],
        quality_name: &str,
    ) -> Result<Vec<f64>> {
        let quality_name = cstr("quality name", quality_name)?;
        let mut out = OutArray::<f64>::new();
        // SAFETY: valid slice, C string and out-pointers.
        check("gmshModelMeshGetElementQualities", |ierr| unsafe {
            sys::gmshModelMeshGetElementQualities(
                element_tags.as_ptr(),
                element_tags.len(),
                out.ptr(),
                out.len(),
                quality_name.as_ptr(),
                0,
                1,
                ierr,
            )
        })?;
        Ok(out.to_vec())
    }

    /// Adds a mesh size field of type `kind` (e.g. `"Distance"`,
    /// `"Threshold"`, `"Box"`, `"MathEval"`, `"Min"`) and returns its tag
    /// (`gmshModelMeshFieldAdd`).
    pub fn mesh_field_add(&self, kind: &str) -> Result<i32> {
        let kind = cstr("field type", kind)?;
        // SAFETY: valid C string.
        check("gmshModelMeshFieldAdd", |ierr| unsafe {
            sys::gmshModelMeshFieldAdd(kind.as_ptr(), -1, ierr)
        })
    }

    /// Sets the numerical option `option` of field `tag`
    /// (`gmshModelMeshFieldSetNumber`).
    pub fn mesh_field_set_number(&self, tag: i32, option: &str, v: f64) -> Result<()> {
        let option = cstr("field option", option)?;
        // SAFETY: valid C string.
        check("gmshModelMeshFieldSetNumber", |ierr| unsafe {
            sys::gmshModelMeshFieldSetNumber(tag, option.as_ptr(), v, ierr)
        })
    }

    /// Sets the list option `option` of field `tag`, e.g. `"SurfacesList"`
    /// (`gmshModelMeshFieldSetNumbers`).
    pub fn mesh_field_set_numbers(&self, tag: i32, option: &str, values: &[f64]) -> Result<()> {
        let option = cstr("field option", option)?;
        // SAFETY: valid C string and slice.
        check("gmshModelMeshFieldSetNumbers", |ierr| unsafe {
            sys::gmshModelMeshFieldSetNumbers(
                tag,
                option.as_ptr(),
                values.as_ptr(),
                values.len(),
                ierr,
            )
        })
    }

    /// Uses field `tag` as the background mesh size field
    /// (`gmshModelMeshFieldSetAsBackgroundMesh`).
    pub fn mesh_field_set_as_background_mesh(&self, tag: i32) -> Result<()> {
        // SAFETY: scalar arguments only.
        check("gmshModelMeshFieldSetAsBackgroundMesh", |ierr| unsafe {
            sys::gmshModelMeshFieldSetAsBackgroundMesh(tag, ierr)
        })
    }

    /// The coordinates of mesh node `tag` and the (dim, tag) of the entity
    /// it is classified on (`gmshModelMeshGetNode`).
    pub fn mesh_get_node(&self, tag: usize) -> Result<([f64; 3], DimTag)> {
        let mut coord = OutArray::<f64>::new();
        let mut param = OutArray::<f64>::new();
        let (mut dim, mut entity) = (0, 0);
        // SAFETY: valid out-pointers; arrays freed by OutArray.
        check("gmshModelMeshGetNode", |ierr| unsafe {
            sys::gmshModelMeshGetNode(
                tag,
                coord.ptr(),
                coord.len(),
                param.ptr(),
                param.len(),
                &mut dim,
                &mut entity,
                ierr,
            )
        })?;
        let c = coord.to_vec();
        Ok(([c[0], c[1], c[2]], (dim, entity)))
    }

    /// Moves mesh node `tag` to `coord` (parametric coordinates dropped)
    /// (`gmshModelMeshSetNode`).
    pub fn mesh_set_node(&self, tag: usize, coord: [f64; 3]) -> Result<()> {
        // SAFETY: valid 3-array; no parametric coordinates.
        check("gmshModelMeshSetNode", |ierr| unsafe {
            sys::gmshModelMeshSetNode(tag, coord.as_ptr(), 3, std::ptr::null(), 0, ierr)
        })
    }

    /// Removes the elements `element_tags` from entity (`dim`, `tag`); their
    /// nodes stay (`gmshModelMeshRemoveElements`). An empty list removes
    /// nothing (gmsh itself would remove every element of the entity).
    pub fn mesh_remove_elements(&self, dim: i32, tag: i32, element_tags: &[usize]) -> Result<()> {
        if element_tags.is_empty() {
            return Ok(());
        }
        // SAFETY: valid slice.
        check("gmshModelMeshRemoveElements", |ierr| unsafe {
            sys::gmshModelMeshRemoveElements(
                dim,
                tag,
                element_tags.as_ptr(),
                element_tags.len(),
                ierr,
            )
        })
    }

    /// Adds elements of gmsh type `element_type` to entity `tag` of the
    /// element type's dimension: `node_tags` holds each element's nodes in
    /// turn (`gmshModelMeshAddElementsByType`).
    pub fn mesh_add_elements_by_type(
        &self,
        tag: i32,
        element_type: i32,
        element_tags: &[usize],
        node_tags: &[usize],
    ) -> Result<()> {
        // SAFETY: valid slices.
        check("gmshModelMeshAddElementsByType", |ierr| unsafe {
            sys::gmshModelMeshAddElementsByType(
                tag,
                element_type,
                element_tags.as_ptr(),
                element_tags.len(),
                node_tags.as_ptr(),
                node_tags.len(),
                ierr,
            )
        })
    }

    /// The largest element tag of the mesh (`gmshModelMeshGetMaxElementTag`).
    pub fn mesh_get_max_element_tag(&self) -> Result<usize> {
        let mut max = 0usize;
        // SAFETY: valid out-pointer.
        check("gmshModelMeshGetMaxElementTag", |ierr| unsafe {
            sys::gmshModelMeshGetMaxElementTag(&mut max, ierr)
        })?;
        Ok(max)
    }

    /// Makes the mesh of each entity `tags[i]` of dimension `dim` a copy of
    /// the mesh of `masters[i]` mapped by `affine` (a 4 × 4 matrix by rows,
    /// master to slave) (`gmshModelMeshSetPeriodic`).
    pub fn mesh_set_periodic(
        &self,
        dim: i32,
        tags: &[i32],
        masters: &[i32],
        affine: &[f64; 16],
    ) -> Result<()> {
        // SAFETY: valid slices.
        check("gmshModelMeshSetPeriodic", |ierr| unsafe {
            sys::gmshModelMeshSetPeriodic(
                dim,
                tags.as_ptr(),
                tags.len(),
                masters.as_ptr(),
                masters.len(),
                affine.as_ptr(),
                affine.len(),
                ierr,
            )
        })
    }

    /// Adds nodes `node_tags` at `coords` (`[x, y, z, ...]`) to entity
    /// `(dim, tag)` (`gmshModelMeshAddNodes`, no parametric coordinates).
    pub fn mesh_add_nodes(
        &self,
        dim: i32,
        tag: i32,
        node_tags: &[usize],
        coords: &[f64],
    ) -> Result<()> {
        // SAFETY: valid slices.
        check("gmshModelMeshAddNodes", |ierr| unsafe {
            sys::gmshModelMeshAddNodes(
                dim,
                tag,
                node_tags.as_ptr(),
                node_tags.len(),
                coords.as_ptr(),
                coords.len(),
                std::ptr::null(),
                0,
                ierr,
            )
        })
    }

    /// The largest node tag of the mesh (`gmshModelMeshGetMaxNodeTag`).
    pub fn mesh_get_max_node_tag(&self) -> Result<usize> {
        let mut max = 0usize;
        // SAFETY: valid out-pointer.
        check("gmshModelMeshGetMaxNodeTag", |ierr| unsafe {
            sys::gmshModelMeshGetMaxNodeTag(&mut max, ierr)
        })?;
        Ok(max)
    }

    /// Clears the mesh (nodes and elements) of the entities `dimtags` only
    /// (`gmshModelMeshClear`); an entity on the boundary of a meshed one
    /// cannot be cleared.
    pub fn mesh_clear_entities(&self, dimtags: &[DimTag]) -> Result<()> {
        let flat = flatten(dimtags);
        // SAFETY: valid slice.
        check("gmshModelMeshClear", |ierr| unsafe {
            sys::gmshModelMeshClear(flat.as_ptr(), flat.len(), ierr)
        })
    }

    /// Clears the whole mesh of the current model (`gmshModelMeshClear`).
    pub fn mesh_clear(&self) -> Result<()> {
        // SAFETY: empty dimTags = all entities.
        check("gmshModelMeshClear", |ierr| unsafe {
            sys::gmshModelMeshClear(std::ptr::null(), 0, ierr)
        })
    }
}
