//! A glTF primitive's texture coordinates (`TEXCOORD_0`) and the image its material's base
//! colour names, read as the positions are: every accessor range checked first.
//!
//! glTF's texture coordinates put `(0, 0)` at the image's top-left corner, `v` running
//! down (glTF 2.0 §3.7.2.1, "Meshes": "the origin of the UV coordinate system is the
//! top-left corner of the image"); irsig's put it at the bottom-left, `v` running up, as
//! OBJ's do. A glTF coordinate `(u, v)` is irsig's `(u, 1 − v)`, turned here once.

use std::path::Path;

use gltf::accessor::{DataType, Dimensions};

use super::{Walk, decode_data_uri, inside, local_relative_path};
use crate::ParseError;
use crate::mesh::EmbeddedImage;

impl Walk<'_> {
    /// The `TEXCOORD_0` of a primitive of `vertex_count` vertices, in irsig's convention;
    /// `None` when it has none.
    ///
    /// # Errors
    /// An accessor that is not a `VEC2` of floats or normalised unsigned bytes or shorts
    /// (the three glTF 2.0 allows), whose count is not the positions', whose range runs
    /// past its buffer, or that holds a value that is not finite.
    pub(super) fn texcoords(
        &self,
        primitive: &gltf::Primitive<'_>,
        vertex_count: usize,
        part: &str,
    ) -> Result<Option<Vec<[f64; 2]>>, ParseError> {
        let Some(acc) = primitive.get(&gltf::Semantic::TexCoords(0)) else {
            return Ok(None);
        };
        let at = format!("accessors[{}]", acc.index());
        let size = match (acc.data_type(), acc.normalized()) {
            (DataType::F32, _) => 4,
            (DataType::U16, true) => 2,
            (DataType::U8, true) => 1,
            (t, normalized) => {
                return Err(self.err(
                    &format!("{at}.componentType"),
                    part,
                    format!(
                        "expected TEXCOORD_0 as float, or normalised unsigned byte or short, \
                         found {t:?}{}",
                        if normalized { "" } else { " (not normalised)" }
                    ),
                ));
            }
        };
        if acc.dimensions() != Dimensions::Vec2 {
            return Err(self.err(
                &format!("{at}.type"),
                part,
                format!("expected TEXCOORD_0 as VEC2, found {:?}", acc.dimensions()),
            ));
        }
        if acc.count() != vertex_count {
            return Err(self.err(
                &format!("{at}.count"),
                part,
                format!(
                    "expected one TEXCOORD_0 per vertex, {vertex_count}, found {}",
                    acc.count()
                ),
            ));
        }
        let (data, stride) = self.accessor_data(&acc, 2 * size, part)?;
        let component = |at: usize| -> f64 {
            match size {
                4 => f64::from(f32::from_le_bytes([
                    data[at],
                    data[at + 1],
                    data[at + 2],
                    data[at + 3],
                ])),
                // Normalised: the integer over its largest value (glTF 2.0 §3.11).
                2 => f64::from(u16::from_le_bytes([data[at], data[at + 1]])) / 65535.0,
                _ => f64::from(data[at]) / 255.0,
            }
        };
        let mut out = Vec::with_capacity(vertex_count);
        for k in 0..vertex_count {
            let [u, v] = [component(k * stride), component(k * stride + size)];
            if !(u.is_finite() && v.is_finite()) {
                return Err(self.err(
                    &at,
                    part,
                    format!("expected finite texture coordinates, found ({u}, {v}) at vertex {k}"),
                ));
            }
            out.push([u, 1.0 - v]);
        }
        Ok(Some(out))
    }

    /// The image a material's base colour texture names, relative to the model's folder;
    /// `None` when it names none, or names one inside the file (a buffer view or a `data:`
    /// URI), which no material map can name by path.
    ///
    /// # Errors
    /// An image URI that is not a local relative path, climbs out of the model's folder or
    /// leads out of it through a symbolic link, at `images[i].uri`.
    pub(super) fn base_color_image(
        &self,
        material: &gltf::Material<'_>,
        base_dir: Option<&Path>,
    ) -> Result<Option<String>, ParseError> {
        let Some(info) = material.pbr_metallic_roughness().base_color_texture() else {
            return Ok(None);
        };
        let image = info.texture().source();
        let gltf::image::Source::Uri { uri, .. } = image.source() else {
            return Ok(None);
        };
        if uri.starts_with("data:") {
            return Ok(None);
        }
        let path = format!("images[{}].uri", image.index());
        let err = |why: String| self.source.error(&path, why);
        let rel = local_relative_path(uri).map_err(err)?;
        if let Some(dir) = base_dir {
            inside(dir, &rel, uri).map_err(err)?;
        }
        Ok(Some(crate::mesh::slash_path(&rel)))
    }

    /// The image a material's base colour texture carries inside the file: a buffer view
    /// of a buffer (a GLB's `BIN` chunk, or any buffer already loaded), or a `data:` URI;
    /// `None` when the material names none or names a file.
    ///
    /// # Errors
    /// A buffer view that runs past its buffer, or a `data:` URI that is not base64, at
    /// `images[i]`.
    pub(super) fn base_color_embedded(
        &mut self,
        material: &gltf::Material<'_>,
    ) -> Result<Option<EmbeddedImage>, ParseError> {
        let Some(info) = material.pbr_metallic_roughness().base_color_texture() else {
            return Ok(None);
        };
        let image = info.texture().source();
        let index = image.index();
        if let Some(read) = self.embedded.get(&index) {
            return Ok(Some(read.clone()));
        }
        let at = |field: &str| format!("images[{index}]{field}");
        let (mime_type, bytes) = match image.source() {
            gltf::image::Source::View { view, mime_type } => {
                let buffer = self.buffers.get(view.buffer().index());
                let end = view.offset().checked_add(view.length());
                let bytes = match (buffer, end) {
                    (Some(b), Some(end)) if end <= b.len() => b[view.offset()..end].into(),
                    _ => {
                        return Err(self.source.error(
                            &at(".bufferView"),
                            format!(
                                "bufferViews[{}] runs past its buffer, or its buffer does not exist",
                                view.index()
                            ),
                        ));
                    }
                };
                (Some(mime_type.to_owned()), bytes)
            }
            gltf::image::Source::Uri { uri, mime_type } => {
                let Some(rest) = uri.strip_prefix("data:") else {
                    return Ok(None);
                };
                let (media_type, bytes) =
                    decode_data_uri(rest).map_err(|e| self.source.error(&at(".uri"), e))?;
                let stated = mime_type.or((!media_type.is_empty()).then_some(media_type));
                (stated.map(str::to_owned), bytes.into())
            }
        };
        let read = EmbeddedImage {
            index,
            name: image.name().map(str::to_owned),
            mime_type,
            bytes,
        };
        self.embedded.insert(index, read.clone());
        Ok(Some(read))
    }
}
