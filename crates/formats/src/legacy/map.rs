//! The 1990 interaction map (thesis §4.2): one byte per pixel, the material id of the facet
//! a pixel's centre ray hits in the upper nibble and that of the facet its reflection ray
//! hits in the lower (0: none). irsig-trace writes it from the frame it traced,
//! irsig-merge from the truth layers of the tiles it merges; both through this one rule.
//!
//! The bytes are stored as the indices of an indexed-colour PNG whose [`palette`] gives
//! each primary material its own colour: as grey levels, ids 1 to 15 in the upper nibble
//! are 16 to 255 but most pixels of a scene of few materials are near black, and the
//! lower nibble's reflected id moves a level by at most 15. The indices are the 1990
//! bytes, unchanged; a reader that keeps them (Pillow's mode `P`, MATLAB's
//! `[X, map] = imread`, `irsig_raster::read_png_indices`) gets the ids.
//!
//! ```
//! use irsig_formats::legacy::map;
//! assert_eq!(map::pixel(3, 12), Some(0x3c));
//! assert_eq!(map::pixel(16, 0), None);
//! assert_eq!(map::palette()[0], [0, 0, 0]);
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

/// Fifteen colours for ids 1 to 15: Kelly's "twenty-two colours of maximum contrast"
/// (Kelly 1965, *Color Engineering* 3(6), 26–27; sRGB values after Green-Armytage 2010),
/// less the first two, white and black, so that no material looks like nothing hit.
const KELLY: [[u8; 3]; 15] = [
    [0xf3, 0xc3, 0x00], // yellow
    [0x87, 0x56, 0x92], // purple
    [0xf3, 0x84, 0x00], // orange
    [0xa1, 0xca, 0xf1], // light blue
    [0xbe, 0x00, 0x32], // red
    [0xc2, 0xb2, 0x80], // buff
    [0x84, 0x84, 0x82], // grey
    [0x00, 0x88, 0x56], // green
    [0xe6, 0x8f, 0xac], // purplish pink
    [0x00, 0x67, 0xa5], // blue
    [0xf9, 0x93, 0x79], // yellowish pink
    [0x60, 0x4e, 0x97], // violet
    [0xf6, 0xa6, 0x00], // orange yellow
    [0xb3, 0x44, 0x6c], // purplish red
    [0xdc, 0xd3, 0x00], // greenish yellow
];

/// The colour of material `id` (0: black, nothing hit).
fn colour(id: usize) -> [u8; 3] {
    id.checked_sub(1)
        .and_then(|i| KELLY.get(i))
        .copied()
        .unwrap_or([0, 0, 0])
}

/// The map's palette: byte `p·16 + s` shows the primary material `p`'s colour with 30 % of
/// the reflected material `s`'s mixed in when `s` is not 0, so that a surface reads by
/// its own colour and a mirror that sees another facet shows a tint of it. Byte 0
/// (nothing hit, the sky or the terrain) is black.
#[must_use]
pub fn palette() -> [[u8; 3]; 256] {
    std::array::from_fn(|byte| {
        let (p, s) = (colour(byte >> 4), byte & 0xf);
        if s == 0 {
            return p;
        }
        let s = colour(s);
        // (7·p + 3·s) / 10, rounded; at most 2550, so the quotient fits a byte.
        std::array::from_fn(|c| ((7 * u16::from(p[c]) + 3 * u16::from(s[c]) + 5) / 10) as u8)
    })
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

    #[test]
    fn every_material_has_its_own_visible_colour() {
        let palette = palette();
        assert_eq!(palette[0], [0, 0, 0], "nothing hit");
        // Kelly's yellow for id 1 and greenish yellow for id 15, as published.
        assert_eq!(palette[0x10], [0xf3, 0xc3, 0x00]);
        assert_eq!(palette[0xf0], [0xdc, 0xd3, 0x00]);
        for p in 1..16 {
            let own = palette[p << 4];
            // Visible on black: a channel sum of at least 200 of 765 (the darkest, green,
            // 0x00 0x88 0x56, sums to 222).
            let sum: u16 = own.iter().map(|&c| u16::from(c)).sum();
            assert!(sum >= 200, "id {p}: {own:?}");
            for q in (p + 1)..16 {
                assert_ne!(own, palette[q << 4], "ids {p} and {q}");
            }
            // A reflection of another material tints the colour; of itself, it does not.
            for s in 1..16 {
                let tinted = palette[(p << 4) | s];
                assert_eq!(tinted == own, s == p, "primary {p}, reflected {s}");
            }
        }
        // By hand: red (5) reflecting yellow (1): (7·0xbe + 3·0xf3 + 5) / 10 = 206 = 0xce,
        // (7·0 + 3·0xc3 + 5) / 10 = 59, (7·0x32 + 3·0 + 5) / 10 = 35.
        assert_eq!(palette[0x51], [206, 59, 35]);
    }
}
