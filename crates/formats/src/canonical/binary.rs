//! The compact binary raw scene: what `irsig-flatten` writes by default and `irsig-trace`
//! reads, because RON of a million triangles is several times larger and slower (see
//! `BENCHMARKS.md`, section "import and flatten").
//!
//! Layout (all little-endian, no padding, documented in `formats/canonical/raw-scene.md`):
//!
//! | offset | size | field |
//! | --- | --- | --- |
//! | 0 | 8 | magic `IRSIGRAW` |
//! | 8 | 4 | `u32` version, 1 |
//! | 12 | 4 | `u32` flags: bit 0 a texture-coordinate section, bit 1 a per-material temperature section, bits 2–15 reserved 0, 16–31 the terrain's material id (0: none) |
//! | 16 | 8 | `f64` terrain temperature, K |
//! | 24 | 8 | `f64` terrain emissivity |
//! | 32 | 4 | `u32` object count `O` |
//! | 36 | 4 | `u32` position count `P` |
//! | 40 | 4 | `u32` facet count `F` |
//! | 44 | 4 | `u32` byte length `N` of the name block |
//! | 48 | `N` | `O` names, each a `u32` byte length and that many UTF-8 bytes |
//! | 48 + `N` | 24 `P` | positions, `f64` x y z in metres |
//! | … | 28 `F` | facets: `u32` v0 v1 v2, `u16` material, `u16` facet flags, `u32` object, `f64` temperature K |
//! | … | 48 `F` | only when flag bit 0 is set: per facet `f64` u v at each corner (zeros for a facet without) |
//! | … | 4 + 40 `M` | only when flag bit 1 is set: `u32` entry count `M`, then per entry `u32` facet, `u32` count `n` (1 to 4), four `f64` temperatures K (zeros past `n`) |
//!
//! Header flag bit 0 says the texture-coordinate section follows the facets; it is set only
//! when some facet has coordinates, so a scene without them keeps the bytes it had before
//! the section existed. Facet flag bit 0 says the facet has coordinates; the facet flags'
//! other bits are reserved and must be 0. Header flag bit 1 says the per-material
//! temperature section ([`irsig_model::MixTemperatures`]) ends the file; it too is set only
//! when the scene has some, so a scene without keeps its bytes.
//!
//! The reader checks that the file length equals what the header's counts imply before it
//! allocates anything, so a corrupt count cannot make it allocate more than the file holds.

use irsig_model::material_map::MAX_MAP_MATERIALS;
use irsig_model::{MaterialId, MixTemperatures, RawFacet, RawScene, Terrain};

use super::layout::{self, Form, UV_LEN, f64_at, u32_at};
use crate::ParseError;

/// The first eight bytes of a binary raw scene.
pub const MAGIC: &[u8; 8] = b"IRSIGRAW";
/// The layout version this code reads and writes.
pub const VERSION: u32 = 1;
/// Header size in bytes.
pub const HEADER_LEN: usize = 48;
/// Bytes per position.
pub const POSITION_LEN: usize = layout::POSITION_LEN;
/// Bytes per facet.
pub const FACET_LEN: usize = 28;

const FORM: Form = Form {
    magic: MAGIC,
    version: VERSION,
    header_len: HEADER_LEN,
    noun: "raw scene",
    flag_bits: TERRAIN_MATERIAL_BITS | layout::HAS_UV_SECTION | HAS_MIX_SECTION,
};

/// Header flag: the per-material temperature section ends the file.
pub const HAS_MIX_SECTION: u32 = 2;
/// Bytes per entry of the per-material temperature section: `u32` facet, `u32` count and
/// [`MAX_MAP_MATERIALS`] `f64` temperatures.
pub const MIX_LEN: usize = 8 + 8 * MAX_MAP_MATERIALS;

/// Facet flag: the facet has texture coordinates in the section after the facets.
pub const FACET_HAS_UV: u16 = 1;

/// The flag bits that hold the terrain's material id, the high half (bytes 14 and 15), so
/// that the low half stays reserved as it was: 0 is never a material, so a file written
/// before the terrain could name one (flags 0) reads as the constant emissivity.
const TERRAIN_MATERIAL_BITS: u32 = 0xffff_0000;
/// Where the terrain's material id starts in the flags.
const TERRAIN_MATERIAL_SHIFT: u32 = 16;

/// True when `bytes` start with [`MAGIC`].
#[must_use]
pub fn is_binary(bytes: &[u8]) -> bool {
    bytes.starts_with(MAGIC)
}

/// Encodes a raw scene into one buffer; [`write`] streams the same bytes instead.
///
/// # Errors
/// As [`write`], less the I/O errors.
pub fn encode(scene: &RawScene) -> Result<Vec<u8>, std::io::Error> {
    let names_len: usize = scene.objects.iter().map(|n| 4 + n.len()).sum();
    let uv_len = if scene.facets.iter().any(|f| f.uv.is_some()) {
        UV_LEN
    } else {
        0
    };
    let mut out = Vec::with_capacity(
        HEADER_LEN
            + names_len
            + POSITION_LEN * scene.positions_m.len()
            + (FACET_LEN + uv_len) * scene.facets.len()
            + mix_section_len(scene),
    );
    write(scene, &mut out)?;
    Ok(out)
}

/// The bytes of the per-material temperature section: none without entries.
fn mix_section_len(scene: &RawScene) -> usize {
    if scene.mix_temperatures.is_empty() {
        0
    } else {
        4 + MIX_LEN * scene.mix_temperatures.len()
    }
}

/// Writes a raw scene in the binary form, a few hundred kilobytes at a time, so that a
/// million-triangle scene is never held encoded in memory whole (40 MB).
///
/// # Errors
/// A scene with more than `u32::MAX` objects, positions, facets or per-material
/// temperature entries, a name block over 4 GiB, or an entry of more than
/// [`MAX_MAP_MATERIALS`] temperatures, which this layout cannot hold (found before anything
/// is written), or an I/O error from `w`.
pub fn write(scene: &RawScene, w: &mut dyn std::io::Write) -> std::io::Result<()> {
    let count = |n: usize, what: &str| FORM.count(n, what);
    let names_len: usize = scene.objects.iter().map(|n| 4 + n.len()).sum();
    let uv_flags = layout::uv_flags(scene.facets.iter().map(|f| f.uv.as_ref()));
    let mix_count = count(
        scene.mix_temperatures.len(),
        "per-material temperature entries",
    )?;
    if let Some(m) = scene
        .mix_temperatures
        .iter()
        .find(|m| m.temperatures_k.len() > MAX_MAP_MATERIALS)
    {
        return Err(std::io::Error::other(format!(
            "facet {}: {} per-material temperatures, more than the {MAX_MAP_MATERIALS} the \
             binary form holds",
            m.facet,
            m.temperatures_k.len()
        )));
    }
    let mix_flag = if mix_count > 0 { HAS_MIX_SECTION } else { 0 };
    let flags = scene
        .terrain
        .material
        .map_or(0, |m| u32::from(m.0) << TERRAIN_MATERIAL_SHIFT)
        | uv_flags
        | mix_flag;
    let mut header = FORM.start_header(HEADER_LEN + names_len, flags);
    header.extend_from_slice(&scene.terrain.temperature_k.to_le_bytes());
    header.extend_from_slice(&scene.terrain.emissivity.to_le_bytes());
    header.extend_from_slice(&count(scene.objects.len(), "objects")?.to_le_bytes());
    header.extend_from_slice(&count(scene.positions_m.len(), "positions")?.to_le_bytes());
    header.extend_from_slice(&count(scene.facets.len(), "facets")?.to_le_bytes());
    header.extend_from_slice(&count(names_len, "name bytes")?.to_le_bytes());
    for name in &scene.objects {
        header.extend_from_slice(&count(name.len(), "name bytes")?.to_le_bytes());
        header.extend_from_slice(name.as_bytes());
    }
    w.write_all(&header)?;
    layout::write_positions(w, &scene.positions_m)?;
    layout::write_records(w, &scene.facets, FACET_LEN, |f, out| {
        for v in f.vertices {
            out.extend_from_slice(&v.to_le_bytes());
        }
        out.extend_from_slice(&f.material.0.to_le_bytes());
        let facet_flags = if f.uv.is_some() { FACET_HAS_UV } else { 0 };
        out.extend_from_slice(&facet_flags.to_le_bytes());
        out.extend_from_slice(&f.object.to_le_bytes());
        out.extend_from_slice(&f.temperature_k.to_le_bytes());
    })?;
    layout::write_uvs(w, uv_flags, &scene.facets, |f| f.uv.as_ref())?;
    if mix_count == 0 {
        return Ok(());
    }
    w.write_all(&mix_count.to_le_bytes())?;
    layout::write_records(w, &scene.mix_temperatures, MIX_LEN, |m, out| {
        out.extend_from_slice(&m.facet.to_le_bytes());
        // Checked above: at most four, so the count fits.
        out.extend_from_slice(&(m.temperatures_k.len() as u32).to_le_bytes());
        for k in 0..MAX_MAP_MATERIALS {
            let t = m.temperatures_k.get(k).copied().unwrap_or(0.0);
            out.extend_from_slice(&t.to_le_bytes());
        }
    })
}

/// Where the record a validation path names (`positions_m[i]…`, `facets[i]…`, `terrain…`)
/// starts in the encoding of `scene`, so that an error can give its byte offset.
#[must_use]
pub fn offset_of_path(scene: &RawScene, path: &str) -> usize {
    let names: usize = scene.objects.iter().map(|n| 4 + n.len()).sum();
    let positions_at = HEADER_LEN + names;
    let facets_at = positions_at + POSITION_LEN * scene.positions_m.len();
    if let Some(rest) = path.strip_prefix("mix_temperatures") {
        let uv_len = if scene.facets.iter().any(|f| f.uv.is_some()) {
            UV_LEN
        } else {
            0
        };
        let section_at = facets_at + (FACET_LEN + uv_len) * scene.facets.len();
        let entry = rest
            .strip_prefix('[')
            .and_then(|r| r.split(']').next())
            .and_then(|i| i.parse::<usize>().ok());
        return entry.map_or(section_at, |k| section_at + 4 + MIX_LEN * k);
    }
    match layout::record_offset(path, positions_at, facets_at, FACET_LEN) {
        Some(at) => at,
        // The material's id is the flags' high half.
        None if path.starts_with("terrain.material") => 14,
        None if path.starts_with("terrain") => 16,
        None => 0,
    }
}

/// Decodes a binary raw scene. Does not validate the model rules (see
/// [`super::read_raw_scene`], which does).
///
/// # Errors
/// A wrong magic or version, a length that disagrees with the header's counts, a name that
/// runs past its block or is not UTF-8; at the byte offset of the problem.
pub fn decode(file: &str, bytes: &[u8]) -> Result<RawScene, ParseError> {
    let err = |offset: usize, msg: String| ParseError::in_binary(file, offset, msg);
    FORM.check_header(file, bytes)?;
    let objects = u32_at(bytes, 32) as usize;
    let positions = u32_at(bytes, 36) as usize;
    let facets = u32_at(bytes, 40) as usize;
    let names_len = u32_at(bytes, 44) as usize;
    let has_uv_section = u32_at(bytes, 12) & layout::HAS_UV_SECTION != 0;
    let has_mix_section = u32_at(bytes, 12) & HAS_MIX_SECTION != 0;
    let uv_len = if has_uv_section { UV_LEN } else { 0 };
    // u64 arithmetic: u32 counts times record sizes cannot overflow it.
    let body = HEADER_LEN as u64
        + names_len as u64
        + POSITION_LEN as u64 * positions as u64
        + (FACET_LEN + uv_len) as u64 * facets as u64;
    // The section's entry count is its first word: read where the file holds it.
    let mix_entries = match usize::try_from(body) {
        Ok(at) if has_mix_section && bytes.len() >= at.saturating_add(4) => u32_at(bytes, at),
        _ => 0,
    };
    let expected = body
        + if has_mix_section {
            4 + MIX_LEN as u64 * u64::from(mix_entries)
        } else {
            0
        };
    FORM.check_length(file, bytes, expected, || {
        let uvs = if has_uv_section {
            " with texture coordinates"
        } else {
            ""
        };
        let mix = if has_mix_section {
            format!(" and {mix_entries} per-material temperature entries")
        } else {
            String::new()
        };
        format!(
            "{objects} objects ({names_len} name bytes), {positions} positions and {facets} \
             facets{uvs}{mix}"
        )
    })?;
    // From here every count is bounded by the file length.
    if objects.saturating_mul(4) > names_len {
        return Err(err(
            32,
            format!("{objects} object names cannot fit in {names_len} bytes"),
        ));
    }
    let mut names = Vec::with_capacity(objects);
    let names_end = HEADER_LEN + names_len;
    let mut at = HEADER_LEN;
    for i in 0..objects {
        if at + 4 > names_end {
            return Err(err(at, format!("object name {i} runs past the name block")));
        }
        let len = u32_at(bytes, at) as usize;
        at += 4;
        if len > names_end - at {
            return Err(err(at, format!("object name {i} runs past the name block")));
        }
        let name = std::str::from_utf8(&bytes[at..at + len])
            .map_err(|_| err(at, format!("object name {i} is not UTF-8")))?;
        names.push(name.to_owned());
        at += len;
    }
    if at != names_end {
        return Err(err(
            at,
            format!(
                "the name block holds {} bytes after the last name",
                names_end - at
            ),
        ));
    }
    let positions_m =
        layout::read_positions(&bytes[names_end..names_end + POSITION_LEN * positions]);
    let facet_start = names_end + POSITION_LEN * positions;
    let uv_start = facet_start + FACET_LEN * facets;
    let mut out = Vec::with_capacity(facets);
    for (i, c) in bytes[facet_start..uv_start]
        .chunks_exact(FACET_LEN)
        .enumerate()
    {
        // Reserved bits must be 0, so that decoding and encoding are inverse and a later
        // version can give them a meaning.
        let facet_flags = u16::from_le_bytes([c[14], c[15]]);
        let allowed = if has_uv_section { FACET_HAS_UV } else { 0 };
        if facet_flags & !allowed != 0 {
            return Err(err(
                facet_start + FACET_LEN * i + 14,
                format!(
                    "facet {i}: expected facet flags {}, found {facet_flags:#x}",
                    if has_uv_section {
                        "0 or 1"
                    } else {
                        "0 (the header declares no texture coordinates)"
                    }
                ),
            ));
        }
        let uv = layout::read_uv(
            file,
            bytes,
            has_uv_section.then_some(uv_start),
            facet_flags & FACET_HAS_UV != 0,
            i,
        )?;
        out.push(RawFacet {
            vertices: [u32_at(c, 0), u32_at(c, 4), u32_at(c, 8)],
            material: MaterialId(u16::from_le_bytes([c[12], c[13]])),
            object: u32_at(c, 16),
            temperature_k: f64_at(c, 20),
            uv,
        });
    }
    let mix_temperatures = if has_mix_section {
        read_mix_section(
            file,
            bytes,
            uv_start + uv_len * facets,
            mix_entries as usize,
        )?
    } else {
        Vec::new()
    };
    Ok(RawScene {
        mix_temperatures,
        terrain: Terrain {
            temperature_k: f64_at(bytes, 16),
            emissivity: f64_at(bytes, 24),
            material: match (u32_at(bytes, 12) & TERRAIN_MATERIAL_BITS) >> TERRAIN_MATERIAL_SHIFT {
                0 => None,
                // The mask and the shift leave 16 bits.
                id => Some(MaterialId(id as u16)),
            },
        },
        objects: names,
        positions_m,
        facets: out,
    })
}

/// The per-material temperature section from `at` (its count word), whose length the
/// header check has proved: each entry's count 1 to [`MAX_MAP_MATERIALS`] and zeros past it.
fn read_mix_section(
    file: &str,
    bytes: &[u8],
    at: usize,
    entries: usize,
) -> Result<Vec<MixTemperatures>, ParseError> {
    let mut out = Vec::with_capacity(entries);
    for k in 0..entries {
        let start = at + 4 + MIX_LEN * k;
        let c = &bytes[start..start + MIX_LEN];
        let n = u32_at(c, 4) as usize;
        if !(1..=MAX_MAP_MATERIALS).contains(&n) {
            return Err(ParseError::in_binary(
                file,
                start + 4,
                format!(
                    "per-material temperature entry {k}: expected 1 to {MAX_MAP_MATERIALS} \
                     temperatures, found {n}"
                ),
            ));
        }
        if c[8 + 8 * n..].iter().any(|&b| b != 0) {
            return Err(ParseError::in_binary(
                file,
                start + 8 + 8 * n,
                format!(
                    "per-material temperature entry {k}: expected zeros after its {n} \
                     temperatures"
                ),
            ));
        }
        out.push(MixTemperatures {
            facet: u32_at(c, 0),
            temperatures_k: (0..n).map(|i| f64_at(c, 8 + 8 * i)).collect(),
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> RawScene {
        RawScene {
            terrain: Terrain {
                temperature_k: 290.5,
                emissivity: 0.95,
                material: None,
            },
            objects: vec!["car".into(), "ström".into()],
            positions_m: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 1e-9]],
            facets: vec![
                RawFacet {
                    vertices: [0, 1, 2],
                    material: MaterialId(7),
                    temperature_k: 300.25,
                    object: 0,
                    uv: None,
                },
                RawFacet {
                    vertices: [2, 1, 0],
                    material: MaterialId(65535),
                    temperature_k: 1e-3,
                    object: 1,
                    uv: None,
                },
            ],
            mix_temperatures: Vec::new(),
        }
    }

    #[test]
    fn round_trips_bit_exactly() {
        let s = scene();
        let bytes = encode(&s).unwrap();
        // Header, names (4+3, 4+6 bytes: "ö" is two), 3 positions, 2 facets.
        assert_eq!(bytes.len(), 48 + 17 + 3 * 24 + 2 * 28);
        assert_eq!(decode("s.bin", &bytes).unwrap(), s);
    }

    #[test]
    fn the_layout_is_the_documented_one() {
        let bytes = encode(&scene()).unwrap();
        assert_eq!(&bytes[..8], b"IRSIGRAW");
        assert_eq!(bytes[8..12], 1u32.to_le_bytes());
        assert_eq!(bytes[16..24], 290.5f64.to_le_bytes());
        assert_eq!(bytes[32..36], 2u32.to_le_bytes());
        assert_eq!(bytes[40..44], 2u32.to_le_bytes());
        assert_eq!(bytes[48..52], 3u32.to_le_bytes());
        assert_eq!(&bytes[52..55], b"car");
        let facet0 = 48 + 17 + 3 * 24;
        assert_eq!(bytes[facet0 + 12..facet0 + 14], 7u16.to_le_bytes());
        assert_eq!(bytes[facet0 + 20..facet0 + 28], 300.25f64.to_le_bytes());
    }

    #[test]
    fn the_terrains_material_is_the_flags_high_half() {
        // Without one, flags 0: the bytes of a file written before the field existed.
        assert_eq!(encode(&scene()).unwrap()[12..16], [0; 4]);
        let mut s = scene();
        s.terrain.material = Some(MaterialId(0xbeef));
        let bytes = encode(&s).unwrap();
        assert_eq!(bytes[12..16], [0, 0, 0xef, 0xbe]);
        assert_eq!(decode("s.bin", &bytes).unwrap(), s);
        let mut reserved = bytes;
        reserved[12] = 4;
        let e = decode("s.bin", &reserved).unwrap_err();
        assert!(e.message.contains("outside 0xffff0003"), "{e}");
    }

    #[test]
    fn a_scene_of_many_chunks_streams_and_reads_back() {
        // 20,000 facets of 28 bytes: 560,000 bytes, three 256 KiB chunks. Written through
        // a writer that takes at most 5 bytes a call.
        struct Trickle(Vec<u8>);
        impl std::io::Write for Trickle {
            fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
                let n = buf.len().min(5);
                self.0.extend_from_slice(&buf[..n]);
                Ok(n)
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let n = 20_000u32;
        let mut s = scene();
        s.positions_m = (0..n + 2)
            .map(|i| [f64::from(i), 0.5, f64::from(i % 2)])
            .collect();
        s.facets = (0..n)
            .map(|i| RawFacet {
                vertices: [i, i + 2, i + 1],
                material: MaterialId((i % 5) as u16),
                temperature_k: 200.0 + f64::from(i) / 64.0,
                object: i % 2,
                uv: None,
            })
            .collect();
        let mut w = Trickle(Vec::new());
        write(&s, &mut w).unwrap();
        let names = 4 + 3 + 4 + 6;
        assert_eq!(
            w.0.len(),
            48 + names + 24 * (n as usize + 2) + 28 * n as usize
        );
        assert_eq!(decode("s.raw", &w.0).unwrap(), s);
    }

    #[test]
    fn truncation_at_every_length_is_an_error() {
        let bytes = encode(&scene()).unwrap();
        for n in 0..bytes.len() {
            assert!(decode("s.bin", &bytes[..n]).is_err(), "length {n}");
        }
    }

    #[test]
    fn a_huge_declared_count_does_not_allocate() {
        let mut bytes = encode(&scene()).unwrap();
        bytes[40..44].copy_from_slice(&u32::MAX.to_le_bytes());
        let e = decode("s.bin", &bytes).unwrap_err();
        assert!(e.message.contains("4294967295 facets"), "{e}");
        let mut bytes = encode(&scene()).unwrap();
        bytes[32..36].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(decode("s.bin", &bytes).is_err());
    }

    #[test]
    fn texture_coordinates_follow_the_facets_only_when_a_facet_has_them() {
        let plain = encode(&scene()).unwrap();
        let mut s = scene();
        s.facets[1].uv = Some([[0.0, 1.0], [-2.5, 0.125], [1e6, -0.0]]);
        let bytes = encode(&s).unwrap();
        // The same bytes as without, but for header flag bit 0, facet 1's flag and the
        // section: 48 bytes per facet, zeros for facet 0.
        let facets_end = 48 + 17 + 3 * 24 + 2 * 28;
        assert_eq!(bytes.len(), facets_end + 2 * 48);
        assert_eq!(bytes[12], 1);
        let facet1 = 48 + 17 + 3 * 24 + 28;
        assert_eq!(bytes[facet1 + 14..facet1 + 16], [1, 0]);
        let mut masked = bytes[..facets_end].to_vec();
        masked[12] = 0;
        masked[facet1 + 14] = 0;
        assert_eq!(masked, plain);
        assert_eq!(bytes[facets_end..facets_end + 48], [0; 48]);
        assert_eq!(
            bytes[facets_end + 48 + 16..facets_end + 48 + 24],
            (-2.5f64).to_le_bytes()
        );
        assert_eq!(
            bytes[facets_end + 48 + 40..facets_end + 48 + 48],
            (-0.0f64).to_le_bytes()
        );
        assert_eq!(decode("s.bin", &bytes).unwrap(), s);
        for n in 0..bytes.len() {
            assert!(decode("s.bin", &bytes[..n]).is_err(), "length {n}");
        }
        // A facet whose flag says it has none must have a record of zeros.
        let mut stray = bytes.clone();
        stray[facets_end + 3] = 1;
        let e = decode("s.bin", &stray).unwrap_err();
        assert_eq!(e.column, facets_end + 1);
        assert!(
            e.message
                .starts_with("facet 0: expected a texture-coordinate"),
            "{e}"
        );
        // The section's flag without the section: the length disagrees.
        let mut short = plain;
        short[12] = 1;
        let e = decode("s.bin", &short).unwrap_err();
        assert!(e.message.contains("facets with texture coordinates"), "{e}");
    }

    #[test]
    fn per_material_temperatures_end_the_file_only_when_the_scene_has_some() {
        let plain = encode(&scene()).unwrap();
        let mut s = scene();
        s.facets[0].uv = Some([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        let with_uv = encode(&s).unwrap();
        s.mix_temperatures = vec![
            MixTemperatures {
                facet: 1,
                temperatures_k: vec![330.5, 291.25],
            },
            MixTemperatures {
                facet: 0,
                temperatures_k: vec![1e-3, 0.0, 400.0, 5000.0],
            },
        ];
        let bytes = encode(&s).unwrap();
        // The same bytes as without but for header flag bit 1 and the section: a count
        // word and 40 bytes per entry, after the texture coordinates.
        let end = with_uv.len();
        assert_eq!(bytes.len(), end + 4 + 2 * 40);
        assert_eq!(bytes[12], 3);
        let mut masked = bytes[..end].to_vec();
        masked[12] = 1;
        assert_eq!(masked, with_uv);
        assert_eq!(bytes[end..end + 4], 2u32.to_le_bytes());
        assert_eq!(bytes[end + 4..end + 8], 1u32.to_le_bytes());
        assert_eq!(bytes[end + 8..end + 12], 2u32.to_le_bytes());
        assert_eq!(bytes[end + 12..end + 20], 330.5f64.to_le_bytes());
        assert_eq!(bytes[end + 28..end + 44], [0; 16]);
        assert_eq!(bytes[end + 44 + 32..end + 44 + 40], 5000f64.to_le_bytes());
        assert_eq!(decode("s.bin", &bytes).unwrap(), s);
        assert_eq!(encode(&decode("s.bin", &bytes).unwrap()).unwrap(), bytes);
        for n in 0..bytes.len() {
            assert!(decode("s.bin", &bytes[..n]).is_err(), "length {n}");
        }
        // Without texture coordinates the section follows the facets.
        let mut no_uv = s.clone();
        no_uv.facets[0].uv = None;
        let b = encode(&no_uv).unwrap();
        assert_eq!(b.len(), plain.len() + 4 + 80);
        assert_eq!(b[12], 2);
        assert_eq!(decode("s.bin", &b).unwrap(), no_uv);
        // A count outside 1 to 4, and a temperature past the count.
        let mut bad = bytes.clone();
        bad[end + 8] = 5;
        let e = decode("s.bin", &bad).unwrap_err();
        assert_eq!(e.column, end + 8 + 1);
        assert!(
            e.message.contains("expected 1 to 4 temperatures, found 5"),
            "{e}"
        );
        let mut stray = bytes.clone();
        stray[end + 40] = 1;
        let e = decode("s.bin", &stray).unwrap_err();
        assert!(e.message.contains("expected zeros after its 2"), "{e}");
        // A huge entry count is refused by the length check, before any allocation.
        let mut huge = bytes.clone();
        huge[end..end + 4].copy_from_slice(&u32::MAX.to_le_bytes());
        let e = decode("s.bin", &huge).unwrap_err();
        assert!(
            e.message
                .contains("4294967295 per-material temperature entries"),
            "{e}"
        );
        // More temperatures than the form holds cannot be written.
        let mut five = s.clone();
        five.mix_temperatures[0].temperatures_k = vec![300.0; 5];
        assert!(encode(&five).is_err());
        // The model's paths find the entry's record.
        assert_eq!(
            offset_of_path(&s, "mix_temperatures[1].temperatures_k[0]"),
            end + 44
        );
        assert_eq!(offset_of_path(&s, "mix_temperatures"), end);
    }

    #[test]
    fn wrong_version_and_bad_names_are_errors() {
        let mut bytes = encode(&scene()).unwrap();
        bytes[8] = 2;
        assert!(
            decode("s.bin", &bytes)
                .unwrap_err()
                .message
                .contains("version")
        );
        let mut bytes = encode(&scene()).unwrap();
        bytes[48] = 200;
        assert!(decode("s.bin", &bytes).is_err());
        // Bits 1-15 of the flags are reserved (0 is the texture coordinates' section,
        // 16-31 the terrain's material).
        let mut bytes = encode(&scene()).unwrap();
        bytes[12] = 0x80;
        assert!(
            decode("s.bin", &bytes)
                .unwrap_err()
                .message
                .contains("flags")
        );
        let mut bytes = encode(&scene()).unwrap();
        let facet1 = 48 + 17 + 3 * 24 + 28;
        bytes[facet1 + 15] = 1;
        let e = decode("s.bin", &bytes).unwrap_err();
        assert!(
            e.message
                .starts_with("facet 1: expected facet flags 0 (the header declares no"),
            "{e}"
        );
        assert_eq!(e.column, facet1 + 14 + 1);
        let mut bytes = encode(&scene()).unwrap();
        bytes[52] = 0xff;
        assert!(
            decode("s.bin", &bytes)
                .unwrap_err()
                .message
                .contains("UTF-8")
        );
    }
}
