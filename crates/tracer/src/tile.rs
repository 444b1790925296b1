//! Tiles: rectangles of a camera's image rendered on their own
//! ([`crate::Tracer::render_tile`]), so that one frame can be split over several processes
//! or machines and put back together bit for bit.
//!
//! A tile is pixels of the same camera: each pixel's rays, and its random stream (seeded
//! by the pixel's index in the whole image), are those of the whole-frame rendering, so a
//! tile's pixels are the same numbers as the same pixels of [`crate::Tracer::render`].
//!
//! ```
//! use irsig_tracer::Tile;
//! // Tile 6 of a 4 x 4 grid over a 1000 x 600 image: second row, second column.
//! let t = Tile::of_grid(6, 4, 4, 1000, 600).unwrap();
//! assert_eq!((t.x, t.y, t.width, t.height), (250, 150, 250, 150));
//! ```

use std::fmt;

/// A rectangle of an image: `width × height` pixels whose top-left pixel is column `x`,
/// row `y` (pixel (0, 0) is the image's top-left, rows run down).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Tile {
    /// First column.
    pub x: u32,
    /// First row.
    pub y: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

/// Why a tile cannot be cut from an image.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TileError {
    /// The tile has no pixels.
    #[error("the tile {0} has no pixels: expected a width and a height of 1 or more")]
    Empty(Tile),
    /// The tile reaches beyond the image.
    #[error(
        "the tile {tile} lies outside the {width}x{height} image: it reaches column {}, row {} \
         (the last are column {}, row {})",
        (u64::from(tile.x) + u64::from(tile.width)).saturating_sub(1),
        (u64::from(tile.y) + u64::from(tile.height)).saturating_sub(1),
        u64::from(*width).saturating_sub(1),
        u64::from(*height).saturating_sub(1)
    )]
    OutsideImage {
        /// The tile asked for.
        tile: Tile,
        /// Image width.
        width: u32,
        /// Image height.
        height: u32,
    },
    /// A grid tile index or grid that does not fit the image.
    #[error("{0}")]
    Grid(String),
}

impl fmt::Display for Tile {
    /// `X,Y,W,H`, as `irsig-trace --tile` takes it.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{},{},{},{}", self.x, self.y, self.width, self.height)
    }
}

impl Tile {
    /// The whole of a `width × height` image.
    #[must_use]
    pub fn whole(width: u32, height: u32) -> Self {
        Self {
            x: 0,
            y: 0,
            width,
            height,
        }
    }

    /// Tile `index` (from 1, row by row from the top-left) of a `columns × rows` grid over
    /// a `width × height` image. Column `c` (from 0) spans `⌊c·width/columns⌋` up to
    /// `⌊(c+1)·width/columns⌋`, rows likewise, so the tiles cover the image exactly and
    /// differ in size by one pixel at most.
    ///
    /// # Errors
    /// An index outside `1..=columns·rows`, or a grid with more columns than the image has
    /// pixels across (or more rows than down).
    pub fn of_grid(
        index: u32,
        columns: u32,
        rows: u32,
        width: u32,
        height: u32,
    ) -> Result<Self, TileError> {
        if columns == 0 || rows == 0 {
            return Err(TileError::Grid(format!(
                "a {columns}x{rows} grid has no tiles: expected 1 or more columns and rows"
            )));
        }
        let count = u64::from(columns) * u64::from(rows);
        if index == 0 || u64::from(index) > count {
            return Err(TileError::Grid(format!(
                "tile {index} of a {columns}x{rows} grid: expected a tile from 1 to {count}"
            )));
        }
        if columns > width || rows > height {
            return Err(TileError::Grid(format!(
                "a {columns}x{rows} grid does not fit a {width}x{height} image: every tile needs \
                 one pixel or more"
            )));
        }
        let i = index - 1;
        let (c, r) = (i % columns, i / columns);
        let edge = |k: u32, n: u32, size: u32| -> u32 {
            // k ≤ n, so the quotient is at most `size`.
            u32::try_from(u64::from(k) * u64::from(size) / u64::from(n)).unwrap_or(size)
        };
        let (x0, x1) = (edge(c, columns, width), edge(c + 1, columns, width));
        let (y0, y1) = (edge(r, rows, height), edge(r + 1, rows, height));
        Ok(Self {
            x: x0,
            y: y0,
            width: x1 - x0,
            height: y1 - y0,
        })
    }

    /// Checks that the tile has pixels and lies inside a `width × height` image.
    ///
    /// # Errors
    /// [`TileError::Empty`] or [`TileError::OutsideImage`].
    pub fn check(&self, width: u32, height: u32) -> Result<(), TileError> {
        if self.width == 0 || self.height == 0 {
            return Err(TileError::Empty(*self));
        }
        let fits =
            |start: u32, len: u32, size: u32| u64::from(start) + u64::from(len) <= u64::from(size);
        if !fits(self.x, self.width, width) || !fits(self.y, self.height, height) {
            return Err(TileError::OutsideImage {
                tile: *self,
                width,
                height,
            });
        }
        Ok(())
    }

    /// Pixels in the tile.
    #[must_use]
    pub fn pixels(&self) -> usize {
        self.width as usize * self.height as usize
    }

    /// This tile grown by `margin` pixels on every side, clipped to a `width × height`
    /// image.
    #[must_use]
    pub(crate) fn grown(&self, margin: u32, width: u32, height: u32) -> Self {
        let x0 = self.x.saturating_sub(margin);
        let y0 = self.y.saturating_sub(margin);
        let x1 = (self.x + self.width).saturating_add(margin).min(width);
        let y1 = (self.y + self.height).saturating_add(margin).min(height);
        Self {
            x: x0,
            y: y0,
            width: x1 - x0,
            height: y1 - y0,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_covers_the_image_exactly_once() {
        for (columns, rows, width, height) in [
            (4, 4, 1024, 1024),
            (3, 2, 10, 7),
            (1, 1, 5, 3),
            (7, 5, 7, 5),
        ] {
            let mut hits = vec![0u32; (width * height) as usize];
            for i in 1..=columns * rows {
                let t = Tile::of_grid(i, columns, rows, width, height).unwrap();
                t.check(width, height).unwrap();
                for r in t.y..t.y + t.height {
                    for c in t.x..t.x + t.width {
                        hits[(r * width + c) as usize] += 1;
                    }
                }
            }
            assert!(
                hits.iter().all(|&h| h == 1),
                "{columns}x{rows} over {width}x{height}"
            );
        }
    }

    #[test]
    fn grid_tiles_are_numbered_row_by_row_from_one() {
        // 10 columns in 3: 0-2, 3-5, 6-9 (edges at 10/3 = 3 and 20/3 = 6).
        let t = Tile::of_grid(3, 3, 2, 10, 7).unwrap();
        assert_eq!(
            t,
            Tile {
                x: 6,
                y: 0,
                width: 4,
                height: 3
            }
        );
        let t = Tile::of_grid(4, 3, 2, 10, 7).unwrap();
        assert_eq!(
            t,
            Tile {
                x: 0,
                y: 3,
                width: 3,
                height: 4
            }
        );
    }

    #[test]
    fn bad_grids_and_tiles_outside_are_errors() {
        assert!(Tile::of_grid(0, 4, 4, 100, 100).is_err());
        assert!(Tile::of_grid(17, 4, 4, 100, 100).is_err());
        assert!(Tile::of_grid(1, 0, 4, 100, 100).is_err());
        assert!(Tile::of_grid(1, 5, 1, 4, 100).is_err());
        let t = Tile {
            x: 1000,
            y: 0,
            width: 64,
            height: 64,
        };
        let e = t.check(1024, 1024).unwrap_err().to_string();
        assert!(
            e.contains("reaches column 1063") && e.contains("column 1023"),
            "{e}"
        );
        assert!(
            Tile {
                x: u32::MAX,
                y: 0,
                width: 2,
                height: 1
            }
            .check(10, 10)
            .is_err()
        );
        assert!(
            Tile {
                x: 0,
                y: 0,
                width: 0,
                height: 1
            }
            .check(10, 10)
            .is_err()
        );
        assert!(Tile::whole(10, 10).check(10, 10).is_ok());
    }

    #[test]
    fn growing_clips_to_the_image() {
        let t = Tile {
            x: 0,
            y: 5,
            width: 3,
            height: 5,
        };
        assert_eq!(
            t.grown(1, 4, 10),
            Tile {
                x: 0,
                y: 4,
                width: 4,
                height: 6
            }
        );
    }
}
