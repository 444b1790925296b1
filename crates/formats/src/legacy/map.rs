//! The 1990 interaction map (thesis §4.2): one byte per pixel, the material id of the facet
//! a pixel's centre ray hits in the upper nibble and that of the facet its reflection ray
//! hits in the lower (0: none), stored as an 8-bit grey image. irsig-trace writes it from
//! the frame it traced, irsig-merge from the truth layers of the tiles it merges; both
//! through this one rule.
//!
//! ```
//! use irsig_formats::legacy::map;
//! assert_eq!(map::pixel(3, 12), Some(0x3c));
//! assert_eq!(map::pixel(16, 0), None);
//! ```

/// The largest material id a nibble holds.
pub const MAX_ID: u16 = 15;

/// The map's byte for a pixel whose centre ray hit material `primary` and whose reflection
/// ray hit `secondary` (0: nothing); `None` when an id does not fit in four bits.
#[must_use]
pub fn pixel(primary: u16, secondary: u16) -> Option<u8> {
    let p = u8::try_from(primary)
        .ok()
        .filter(|&p| u16::from(p) <= MAX_ID)?;
    let s = u8::try_from(secondary)
        .ok()
        .filter(|&s| u16::from(s) <= MAX_ID)?;
    Some((p << 4) | s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_share_a_byte_primary_first() {
        assert_eq!(pixel(0, 0), Some(0));
        assert_eq!(pixel(15, 15), Some(0xff));
        assert_eq!(pixel(1, 0), Some(0x10));
        assert_eq!(pixel(0, 16), None);
        assert_eq!(pixel(300, 1), None);
    }
}
