//! A glTF primitive's geometry: its vertices' positions in world space, its indices and
//! its triangles' corners, every accessor range checked before it is touched.

use gltf::accessor::{DataType, Dimensions};
use gltf::mesh::Mode;

use super::{Matrix, Walk, determinant3};
use crate::ParseError;

impl Walk<'_> {
    /// The JSON path of a primitive's `POSITION` accessor and its vertices' positions, in
    /// world space (`world`: its node's transform).
    ///
    /// # Errors
    /// No `POSITION`, one that is not a `VEC3` of floats, whose range runs past its buffer,
    /// or a position that is not finite once transformed.
    pub(super) fn positions(
        &self,
        primitive: &gltf::Primitive<'_>,
        world: &Matrix,
        part: &str,
        path: &str,
    ) -> Result<(String, Vec<[f64; 3]>), ParseError> {
        let positions = primitive.get(&gltf::Semantic::Positions).ok_or_else(|| {
            self.err(
                &format!("{path}.attributes"),
                part,
                "expected a POSITION attribute, found none",
            )
        })?;
        let pos_at = format!("accessors[{}]", positions.index());
        if positions.data_type() != DataType::F32 {
            return Err(self.err(
                &format!("{pos_at}.componentType"),
                part,
                format!(
                    "expected POSITION as float (5126), found {:?}",
                    positions.data_type()
                ),
            ));
        }
        if positions.dimensions() != Dimensions::Vec3 {
            return Err(self.err(
                &format!("{pos_at}.type"),
                part,
                format!(
                    "expected POSITION as VEC3, found {:?}",
                    positions.dimensions()
                ),
            ));
        }
        let (data, stride) = self.accessor_data(&positions, 12, part)?;
        let vertex_count = positions.count();
        let f32_at = |b: &[u8], at: usize| -> f32 {
            let mut a = [0; 4];
            a.copy_from_slice(&b[at..at + 4]);
            f32::from_le_bytes(a)
        };
        let mut new_positions = Vec::with_capacity(vertex_count);
        for k in 0..vertex_count {
            let p = [
                f64::from(f32_at(data, k * stride)),
                f64::from(f32_at(data, k * stride + 4)),
                f64::from(f32_at(data, k * stride + 8)),
            ];
            let mut w = [0.0; 3];
            for (r, v) in w.iter_mut().enumerate() {
                *v = world[0][r] * p[0] + world[1][r] * p[1] + world[2][r] * p[2] + world[3][r];
            }
            if !w.iter().all(|v| v.is_finite()) {
                return Err(self.err(
                    &pos_at,
                    part,
                    format!("expected finite positions, found {p:?} at vertex {k}"),
                ));
            }
            new_positions.push(w);
        }
        Ok((pos_at, new_positions))
    }

    /// A primitive's indices (`0..vertex_count` when it has none), each checked to be one
    /// of the `vertex_count` vertices of accessor `pos_at`, and a triangle list's count a
    /// multiple of 3.
    ///
    /// # Errors
    /// An index accessor that is not of unsigned SCALARs or runs past its buffer, an
    /// index past the vertices, or a triangle list of a count that is not a multiple of 3.
    pub(super) fn indices(
        &self,
        primitive: &gltf::Primitive<'_>,
        mode: Mode,
        pos_at: &str,
        vertex_count: usize,
        indices_at: &str,
        part: &str,
    ) -> Result<Vec<u32>, ParseError> {
        let indices: Vec<u32> = match primitive.indices() {
            None => (0..u32::try_from(vertex_count).unwrap_or(u32::MAX)).collect(),
            Some(acc) => self.index_values(&acc, part)?,
        };
        if let Some((k, &i)) = indices
            .iter()
            .enumerate()
            .find(|&(_, &i)| i as usize >= vertex_count)
        {
            return Err(self.err(
                indices_at,
                part,
                format!("index {k} is {i}, past the {vertex_count} vertices of {pos_at}"),
            ));
        }
        if mode == Mode::Triangles && indices.len() % 3 != 0 {
            let (at, what) = match primitive.indices() {
                Some(_) => (indices_at, "indices"),
                None => (pos_at, "vertices (no indices)"),
            };
            return Err(self.err(
                at,
                part,
                format!(
                    "a triangle list needs a multiple of 3 {what}, found {}",
                    indices.len()
                ),
            ));
        }
        Ok(indices)
    }

    /// The values of an index accessor: u8, u16 or u32 SCALARs.
    fn index_values(&self, acc: &gltf::Accessor<'_>, part: &str) -> Result<Vec<u32>, ParseError> {
        let size = match (acc.data_type(), acc.dimensions()) {
            (DataType::U8, Dimensions::Scalar) => 1,
            (DataType::U16, Dimensions::Scalar) => 2,
            (DataType::U32, Dimensions::Scalar) => 4,
            (t, d) => {
                return Err(self.err(
                    &format!("accessors[{}]", acc.index()),
                    part,
                    format!("expected u8, u16 or u32 SCALAR indices, found {t:?} {d:?}"),
                ));
            }
        };
        let (data, stride) = self.accessor_data(acc, size, part)?;
        Ok((0..acc.count())
            .map(|k| {
                let at = k * stride;
                match size {
                    1 => u32::from(data[at]),
                    2 => u32::from(u16::from_le_bytes([data[at], data[at + 1]])),
                    _ => u32::from_le_bytes([data[at], data[at + 1], data[at + 2], data[at + 3]]),
                }
            })
            .collect())
    }
}

/// The corners of the triangles `mode` makes of `indices`, counter-clockwise once the
/// node's transform `world` is applied.
pub(super) fn corners(mode: Mode, indices: &[u32], world: &Matrix) -> Vec<[u32; 3]> {
    let mut corners: Vec<[u32; 3]> = match mode {
        Mode::Triangles => indices
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect(),
        // glTF 2.0 §3.7.2.1: strip triangle k is (k, k+1, k+2), every other one
        // reversed to keep the winding; fan triangle k is (0, k+1, k+2).
        Mode::TriangleStrip => indices
            .windows(3)
            .enumerate()
            .map(|(k, w)| {
                if k % 2 == 0 {
                    [w[0], w[1], w[2]]
                } else {
                    [w[1], w[0], w[2]]
                }
            })
            .collect(),
        _ => match indices.split_first() {
            Some((&hub, rest)) => rest.windows(2).map(|w| [hub, w[0], w[1]]).collect(),
            None => Vec::new(),
        },
    };
    if determinant3(world) < 0.0 {
        // A mirroring transform turns counter-clockwise into clockwise.
        for c in &mut corners {
            c.swap(1, 2);
        }
    }
    corners
}
