//! Tiles of a frame put back together: rasters that each say which part of which frame
//! they are ([`crate::FramePart`]) become the frame, with the part of the whole frame, so
//! that its EXR is byte for byte the frame rendered whole.
//!
//! The layout is checked from the headers alone ([`Layout::check`] over
//! [`crate::RasterInfo`]s) before a pixel is decoded: every tile must name the same run,
//! frame size and layers; the tiles must not overlap and must leave no pixel of the frame
//! uncovered. Then the tiles are pasted one at a time ([`Layout::paste`]), so that merging
//! holds the frame and one tile, never all of them.
//!
//! ```
//! use irsig_raster::merge::Layout;
//! use irsig_raster::{FramePart, Raster};
//! let tile = |x: usize, v: f32| {
//!     let part = FramePart { frame_width: 2, frame_height: 1, x, y: 0, run: "run-1".into() };
//!     let mut r = Raster::new(1, 1).with_part(part);
//!     r.push_layer("radiance", "W m^-2 sr^-1", vec![v]).unwrap();
//!     r
//! };
//! let (a, b) = (tile(0, 1.5), tile(1, 2.5));
//! let infos = [("a.exr".to_owned(), a.info()), ("b.exr".to_owned(), b.info())];
//! let layout = Layout::check(&infos).unwrap();
//! let mut frame = layout.frame();
//! layout.paste(&mut frame, "a.exr", &a).unwrap();
//! layout.paste(&mut frame, "b.exr", &b).unwrap();
//! assert_eq!(frame.layers[0].data, vec![1.5, 2.5]);
//! ```

use crate::{FramePart, Layer, Raster, RasterInfo};

/// Why tiles cannot be merged. Each names the files at fault.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum MergeError {
    /// Nothing to merge.
    #[error("no tiles to merge")]
    NoTiles,
    /// A file that says nothing of the frame it belongs to.
    #[error(
        "`{0}` says nothing of the frame it is part of (no `irsig.run` attribute): it was not \
         written by irsig-trace, or by an older irsig-trace"
    )]
    NotAPart(String),
    /// Two tiles made by different runs.
    #[error(
        "`{name}` and `{first}` come from different runs (a different scene, materials, view, \
         band, atmosphere or option): run {run} against {first_run}"
    )]
    DifferentRun {
        /// The tile at fault.
        name: String,
        /// The first tile.
        first: String,
        /// Its run.
        run: String,
        /// The first tile's run.
        first_run: String,
    },
    /// Two tiles of frames of different sizes.
    #[error(
        "`{name}` is part of a {width}x{height} frame, `{first}` of a {first_width}x{first_height} one"
    )]
    DifferentFrame {
        /// The tile at fault.
        name: String,
        /// The first tile.
        first: String,
        /// Its frame's columns.
        width: usize,
        /// Its frame's rows.
        height: usize,
        /// The first tile's frame's columns.
        first_width: usize,
        /// The first tile's frame's rows.
        first_height: usize,
    },
    /// Two tiles with different layers.
    #[error("`{name}` has the layers {layers}, `{first}` has {first_layers}")]
    DifferentLayers {
        /// The tile at fault.
        name: String,
        /// The first tile.
        first: String,
        /// Its layers, `name [unit]`, comma-separated.
        layers: String,
        /// The first tile's layers.
        first_layers: String,
    },
    /// Two tiles of one run whose comments (their provenance) differ.
    #[error(
        "`{name}` and `{first}` are of one run but say different things of what made them \
         (their comments: the inputs' names, or the sensor stage's)"
    )]
    DifferentComments {
        /// The tile.
        name: String,
        /// The first tile.
        first: String,
    },
    /// Two tiles cover the same pixel.
    #[error(
        "`{name}` ({rect}) and `{other}` ({other_rect}) overlap: both hold pixel (column \
         {column}, row {row})"
    )]
    Overlap {
        /// One tile.
        name: String,
        /// Its rectangle, `columns A-B, rows C-D`.
        rect: String,
        /// The other tile.
        other: String,
        /// Its rectangle.
        other_rect: String,
        /// The first pixel both hold (in the order rows are checked).
        column: usize,
        /// Its row.
        row: usize,
    },
    /// A pixel of the frame no tile covers.
    #[error(
        "no tile holds pixel (column {column}, row {row}) of the {width}x{height} frame: a tile \
         is missing (columns {column}-{gap_end} of that row are uncovered)"
    )]
    Missing {
        /// The pixel's column.
        column: usize,
        /// Its row.
        row: usize,
        /// The last uncovered column of the gap on that row.
        gap_end: usize,
        /// Frame columns.
        width: usize,
        /// Frame rows.
        height: usize,
    },
    /// A tile that does not lie inside the frame it names.
    #[error("`{0}`: {1}")]
    Outside(String, String),
    /// A tile whose pixels are not what its header said when the layout was checked.
    #[error("`{0}` is not the tile the layout was checked with")]
    Changed(String),
}

/// The frame a set of tiles makes up, checked: run, size, layers, and where each tile goes.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// The frame's columns.
    pub width: usize,
    /// The frame's rows.
    pub height: usize,
    /// The frame's layers, `(name, unit)`, in order.
    pub layers: Vec<(String, String)>,
    /// The run every tile names.
    pub run: String,
    /// The comments every tile holds (what made it: irsig-trace's provenance).
    pub comments: Option<String>,
    /// Each tile's name and header, in the order given.
    tiles: Vec<(String, RasterInfo)>,
}

impl Layout {
    /// Checks that `tiles` (a name for messages, and the header of each) are the parts of
    /// one frame: one run, one frame size, the same layers, no pixel in two tiles and none
    /// in no tile.
    ///
    /// # Errors
    /// The first [`MergeError`] found, naming the files.
    pub fn check(tiles: &[(String, RasterInfo)]) -> Result<Self, MergeError> {
        let Some((first, first_info)) = tiles.first() else {
            return Err(MergeError::NoTiles);
        };
        let part_of = |name: &String, info: &RasterInfo| -> Result<FramePart, MergeError> {
            info.part
                .clone()
                .ok_or_else(|| MergeError::NotAPart(name.clone()))
        };
        let first_part = part_of(first, first_info)?;
        for (name, info) in tiles {
            let part = part_of(name, info)?;
            if info.width == 0 || info.height == 0 {
                return Err(MergeError::Outside(name.clone(), "it has no pixels".into()));
            }
            part.check(info.width, info.height)
                .map_err(|e| MergeError::Outside(name.clone(), e.to_string()))?;
            if part.run != first_part.run {
                return Err(MergeError::DifferentRun {
                    name: name.clone(),
                    first: first.clone(),
                    run: part.run,
                    first_run: first_part.run.clone(),
                });
            }
            if (part.frame_width, part.frame_height)
                != (first_part.frame_width, first_part.frame_height)
            {
                return Err(MergeError::DifferentFrame {
                    name: name.clone(),
                    first: first.clone(),
                    width: part.frame_width,
                    height: part.frame_height,
                    first_width: first_part.frame_width,
                    first_height: first_part.frame_height,
                });
            }
            if info.comments != first_info.comments {
                return Err(MergeError::DifferentComments {
                    name: name.clone(),
                    first: first.clone(),
                });
            }
            if info.layers != first_info.layers {
                return Err(MergeError::DifferentLayers {
                    name: name.clone(),
                    first: first.clone(),
                    layers: describe_layers(&info.layers),
                    first_layers: describe_layers(&first_info.layers),
                });
            }
        }
        let layout = Self {
            width: first_part.frame_width,
            height: first_part.frame_height,
            layers: first_info.layers.clone(),
            run: first_part.run,
            comments: first_info.comments.clone(),
            tiles: tiles.to_vec(),
        };
        layout.check_coverage()?;
        Ok(layout)
    }

    /// Every pixel in exactly one tile. Which tiles cover a row changes only at a tile's
    /// first row or the row after its last, so those rows are the only ones to look at:
    /// an overlap begins on the first row of one of the two tiles, a gap on the first row
    /// of the frame or the row after some tile's last.
    fn check_coverage(&self) -> Result<(), MergeError> {
        let rect = |i: usize| {
            let (_, info) = &self.tiles[i];
            let p = info.part.as_ref().map_or((0, 0), |p| (p.x, p.y));
            (p.0, p.1, p.0 + info.width, p.1 + info.height)
        };
        let mut rows: Vec<usize> = vec![0];
        for i in 0..self.tiles.len() {
            let (_, y0, _, y1) = rect(i);
            rows.push(y0);
            if y1 < self.height {
                rows.push(y1);
            }
        }
        rows.sort_unstable();
        rows.dedup();
        for row in rows {
            let mut spans: Vec<(usize, usize, usize)> = (0..self.tiles.len())
                .filter_map(|i| {
                    let (x0, y0, x1, y1) = rect(i);
                    (y0..y1).contains(&row).then_some((x0, x1, i))
                })
                .collect();
            spans.sort_unstable();
            let mut covered = 0;
            let mut last: Option<usize> = None;
            for (x0, x1, i) in spans {
                if x0 < covered {
                    let j = last.unwrap_or(i);
                    return Err(MergeError::Overlap {
                        name: self.tiles[i].0.clone(),
                        rect: self.describe_rect(i),
                        other: self.tiles[j].0.clone(),
                        other_rect: self.describe_rect(j),
                        column: x0,
                        row,
                    });
                }
                if x0 > covered {
                    return Err(self.missing(covered, x0, row));
                }
                covered = x1;
                last = Some(i);
            }
            if covered < self.width {
                return Err(self.missing(covered, self.width, row));
            }
        }
        Ok(())
    }

    fn missing(&self, from: usize, to: usize, row: usize) -> MergeError {
        MergeError::Missing {
            column: from,
            row,
            gap_end: to - 1,
            width: self.width,
            height: self.height,
        }
    }

    fn describe_rect(&self, i: usize) -> String {
        let (_, info) = &self.tiles[i];
        let (x, y) = info.part.as_ref().map_or((0, 0), |p| (p.x, p.y));
        format!(
            "columns {}-{}, rows {}-{}",
            x,
            x + info.width - 1,
            y,
            y + info.height - 1
        )
    }

    /// An empty frame of this layout's size and layers (zeros), the whole frame of its run,
    /// ready for [`Self::paste`].
    #[must_use]
    pub fn frame(&self) -> Raster {
        let n = self.width * self.height;
        Raster {
            width: self.width,
            height: self.height,
            layers: self
                .layers
                .iter()
                .map(|(name, unit)| Layer {
                    name: name.clone(),
                    unit: unit.clone(),
                    data: vec![0.0; n],
                })
                .collect(),
            part: Some(FramePart::whole(self.width, self.height, self.run.clone())),
            comments: self.comments.clone(),
        }
    }

    /// Copies tile `name` (one of those the layout was checked with, decoded) into `frame`
    /// (from [`Self::frame`]).
    ///
    /// # Errors
    /// [`MergeError::Changed`] when the tile's size, place, run or layers are not those its
    /// header showed to [`Self::check`], or `frame` is not this layout's.
    pub fn paste(&self, frame: &mut Raster, name: &str, tile: &Raster) -> Result<(), MergeError> {
        let known = self
            .tiles
            .iter()
            .any(|(n, info)| n == name && *info == tile.info());
        let frame_ok = frame.width == self.width
            && frame.height == self.height
            && frame.layers.len() == self.layers.len();
        if !known || !frame_ok {
            return Err(MergeError::Changed(name.to_owned()));
        }
        let Some(p) = &tile.part else {
            return Err(MergeError::NotAPart(name.to_owned()));
        };
        let w = tile.width;
        for (to, from) in frame.layers.iter_mut().zip(&tile.layers) {
            for (r, src) in from.data.chunks_exact(w).enumerate() {
                let start = (p.y + r) * self.width + p.x;
                to.data[start..start + w].copy_from_slice(src);
            }
        }
        Ok(())
    }
}

impl Raster {
    /// What this raster's EXR header would say: size, layers and frame part.
    #[must_use]
    pub fn info(&self) -> RasterInfo {
        RasterInfo {
            width: self.width,
            height: self.height,
            layers: self
                .layers
                .iter()
                .map(|l| (l.name.clone(), l.unit.clone()))
                .collect(),
            part: self.part.clone(),
            comments: self.comments.clone(),
        }
    }
}

fn describe_layers(layers: &[(String, String)]) -> String {
    layers
        .iter()
        .map(|(n, u)| {
            if u.is_empty() {
                n.clone()
            } else {
                format!("{n} [{u}]")
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{exr_bytes, read_exr, read_exr_info};

    /// A `w × h` frame of two layers whose samples encode their pixel.
    fn whole(w: usize, h: usize) -> Raster {
        let mut r = Raster::new(w, h).with_part(FramePart::whole(w, h, "abc"));
        let n = w * h;
        r.push_layer(
            "radiance",
            "W m^-2 sr^-1",
            (0..n).map(|i| i as f32 * 0.5).collect(),
        )
        .unwrap();
        r.push_layer("range", "m", (0..n).map(|i| 1000.0 - i as f32).collect())
            .unwrap();
        r
    }

    /// The rectangle `(x, y, w, h)` of `frame` as a tile.
    fn cut(frame: &Raster, (x, y, w, h): (usize, usize, usize, usize)) -> Raster {
        let mut part = frame.part.clone().unwrap();
        part.x = x;
        part.y = y;
        let mut t = Raster::new(w, h).with_part(part);
        for l in &frame.layers {
            let data = (0..h)
                .flat_map(|r| l.data[(y + r) * frame.width + x..][..w].to_vec())
                .collect();
            t.push_layer(l.name.clone(), l.unit.clone(), data).unwrap();
        }
        t
    }

    fn merge(tiles: &[(String, Raster)]) -> Result<Raster, MergeError> {
        let infos: Vec<_> = tiles.iter().map(|(n, t)| (n.clone(), t.info())).collect();
        let layout = Layout::check(&infos)?;
        let mut frame = layout.frame();
        for (n, t) in tiles {
            layout.paste(&mut frame, n, t)?;
        }
        Ok(frame)
    }

    fn tiles(frame: &Raster, rects: &[(usize, usize, usize, usize)]) -> Vec<(String, Raster)> {
        rects
            .iter()
            .enumerate()
            .map(|(i, &r)| (format!("t{i}.exr"), cut(frame, r)))
            .collect()
    }

    const GRID: [(usize, usize, usize, usize); 4] =
        [(0, 0, 3, 2), (3, 0, 4, 2), (0, 2, 5, 3), (5, 2, 2, 3)];

    #[test]
    fn merged_tiles_write_the_whole_frames_bytes() {
        let frame = whole(7, 5);
        // Through the files: each tile written, read back, merged, written.
        let files: Vec<(String, Vec<u8>)> = tiles(&frame, &GRID)
            .iter()
            .map(|(n, t)| (n.clone(), exr_bytes(t).unwrap()))
            .collect();
        let infos: Vec<_> = files
            .iter()
            .map(|(n, b)| (n.clone(), read_exr_info(b).unwrap()))
            .collect();
        let layout = Layout::check(&infos).unwrap();
        let mut merged = layout.frame();
        for (n, b) in files.iter().rev() {
            layout.paste(&mut merged, n, &read_exr(b).unwrap()).unwrap();
        }
        assert_eq!(merged, frame);
        assert_eq!(exr_bytes(&merged).unwrap(), exr_bytes(&frame).unwrap());
    }

    #[test]
    fn a_missing_tile_is_named_by_its_first_pixel() {
        let frame = whole(7, 5);
        let e = merge(&tiles(&frame, &GRID[..3])).unwrap_err();
        assert_eq!(
            e,
            MergeError::Missing {
                column: 5,
                row: 2,
                gap_end: 6,
                width: 7,
                height: 5
            },
            "{e}"
        );
        // A missing bottom strip.
        let e = merge(&tiles(&frame, &[(0, 0, 7, 4)])).unwrap_err();
        assert!(
            matches!(
                e,
                MergeError::Missing {
                    column: 0,
                    row: 4,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn overlapping_tiles_are_named() {
        let frame = whole(7, 5);
        let mut rects = GRID.to_vec();
        rects[1] = (2, 0, 5, 2);
        let e = merge(&tiles(&frame, &rects)).unwrap_err();
        assert!(
            matches!(&e, MergeError::Overlap { name, other, column: 2, row: 0, .. }
                if name == "t1.exr" && other == "t0.exr"),
            "{e}"
        );
        // The same tile twice.
        let mut t = tiles(&frame, &GRID);
        t.push(("again.exr".into(), t[3].1.clone()));
        assert!(matches!(merge(&t), Err(MergeError::Overlap { .. })));
        // A tile inside another, starting on a later row.
        let mut t = tiles(&frame, &GRID);
        t.push(("inner.exr".into(), cut(&frame, (1, 3, 1, 1))));
        let e = merge(&t).unwrap_err();
        assert!(
            matches!(
                e,
                MergeError::Overlap {
                    column: 1,
                    row: 3,
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn tiles_of_other_runs_frames_or_layers_are_refused() {
        let frame = whole(7, 5);
        let mut t = tiles(&frame, &GRID);
        t[2].1.part.as_mut().unwrap().run = "other".into();
        let e = merge(&t).unwrap_err();
        assert!(
            matches!(&e, MergeError::DifferentRun { name, .. } if name == "t2.exr"),
            "{e}"
        );
        assert!(e.to_string().contains("different runs"), "{e}");

        let mut t = tiles(&frame, &GRID);
        t[1].1.part.as_mut().unwrap().frame_width = 8;
        assert!(matches!(merge(&t), Err(MergeError::DifferentFrame { .. })));

        let mut t = tiles(&frame, &GRID);
        t[3].1.layers.pop();
        let e = merge(&t).unwrap_err();
        assert!(
            e.to_string()
                .contains("has the layers radiance [W m^-2 sr^-1], `t0.exr`"),
            "{e}"
        );

        let mut t = tiles(&frame, &GRID);
        t[0].1.part = None;
        assert_eq!(merge(&t), Err(MergeError::NotAPart("t0.exr".into())));
        assert_eq!(merge(&[]), Err(MergeError::NoTiles));
    }

    #[test]
    fn a_tile_must_be_the_one_checked() {
        let frame = whole(7, 5);
        let t = tiles(&frame, &GRID);
        let infos: Vec<_> = t.iter().map(|(n, r)| (n.clone(), r.info())).collect();
        let layout = Layout::check(&infos).unwrap();
        let mut merged = layout.frame();
        // t1's pixels under t0's name.
        assert_eq!(
            layout.paste(&mut merged, "t0.exr", &t[1].1),
            Err(MergeError::Changed("t0.exr".into()))
        );
    }
}
