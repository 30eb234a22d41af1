//! The roadmap file: the only place that knows its layout.
//!
//! ```text
//! offset  size  field
//!      0     8  magic "VIAROADM"
//!      8     4  format version (u32, little endian)
//!     12     8  payload length in bytes (u64 LE)
//!     20     8  payload checksum (u64 LE, see `checksum`)
//!     28     8  checksum of bytes 0..28 (u64 LE)
//!     36     …  payload: bincode 2 (standard config) of header, nodes, edges, component labels
//! ```
//!
//! Like OMPL's `PlannerDataStorage` the file is marked and signed: the magic says what it is,
//! the version how to read it, and the header records the space, the scene's fingerprint
//! ([`crate::scene::Scene::fingerprint`]), the learning parameters, the local method (a typed
//! [`LocalSpec`], checked on load like a parsed spec string), the seed and the oracle calls
//! spent. No wall-clock time is stored, so the same seed gives
//! the same bytes.
//!
//! Loading checks, in order: magic ([`RoadmapError::NotARoadmap`]), version
//! ([`RoadmapError::WrongVersion`]; every future version keeps magic and version in front),
//! length ([`RoadmapError::Truncated`]), checksums and consistency
//! ([`RoadmapError::Corrupted`]), the local method ([`RoadmapError::UnknownLocalMethod`]), and
//! the scene ([`RoadmapError::ForeignScene`]). The checksums
//! are verified before anything is decoded, and the decoder runs with a byte limit derived from
//! the payload's size, so a corrupted length can neither panic nor allocate without bound.

use super::graph::{Edge, Roadmap};
pub use super::header::Header;
use crate::local::LocalSpec;
use crate::safe_file;
use crate::space::{Space, SpaceKind};
use serde::{Deserialize, Serialize};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// The first eight bytes of every roadmap file.
pub const MAGIC: [u8; 8] = *b"VIAROADM";

/// The version of the layout written by this build (and the only one it reads). Version 3
/// stores the local method as a typed [`LocalSpec`] instead of its spec string.
pub const FORMAT_VERSION: u32 = 3;

/// Bytes before the payload.
pub const FIXED_HEADER_LEN: usize = 36;

/// Why a roadmap cannot be saved or loaded. Each kind of bad file has its own variant.
#[derive(Debug, thiserror::Error)]
pub enum RoadmapError {
    /// Reading or writing the file failed.
    #[error("cannot {action} {path}: {source}")]
    Io {
        /// What was being done ("read", "write", "rename to" …).
        action: &'static str,
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The file does not start with [`MAGIC`].
    #[error("not a viaroad roadmap: the file does not start with the roadmap marker")]
    NotARoadmap,
    /// The file ends early.
    #[error("roadmap file is truncated: it has {found} bytes, {needed} are needed")]
    Truncated {
        /// Bytes present.
        found: u64,
        /// Bytes the header announces (or the fixed header's length).
        needed: u64,
    },
    /// A format version this build does not read.
    #[error(
        "roadmap format version {found} is not supported; this build reads version {supported}"
    )]
    WrongVersion {
        /// Version in the file.
        found: u32,
        /// [`FORMAT_VERSION`].
        supported: u32,
    },
    /// A checksum does not match, or the content does not decode or does not fit together.
    #[error("roadmap file is corrupted: {0}")]
    Corrupted(String),
    /// The roadmap was learnt for another scene.
    #[error(
        "roadmap was learnt for another scene: its fingerprint is {found:016x}, \
         the scene's is {expected:016x}"
    )]
    ForeignScene {
        /// The scene's fingerprint.
        expected: u64,
        /// The fingerprint recorded in the roadmap.
        found: u64,
    },
    /// The recorded local method cannot be rebuilt by this build (its parameters are out of
    /// range).
    #[error(
        "roadmap was learnt with local method `{spec}`, which this build cannot rebuild: {reason}"
    )]
    UnknownLocalMethod {
        /// The recorded spec, as a spec string.
        spec: String,
        /// What is wrong with it.
        reason: String,
    },
    /// The file is not one that may be read or replaced (a device, FIFO, directory …).
    #[error(transparent)]
    File(safe_file::FileError),
    /// Encoding failed (does not happen for roadmaps built by this crate).
    #[error("cannot encode roadmap: {0}")]
    Encode(String),
}

impl RoadmapError {
    /// Keeps the I/O failures in [`RoadmapError::Io`], the rest in [`RoadmapError::File`].
    fn from_file(e: safe_file::FileError) -> Self {
        match e {
            safe_file::FileError::Io {
                action,
                path,
                source,
            } => RoadmapError::Io {
                action,
                path,
                source,
            },
            other => RoadmapError::File(other),
        }
    }
}

/// The payload as written (borrowing the roadmap).
#[derive(Serialize)]
struct PayloadRef<'a> {
    header: &'a Header,
    nodes: &'a [f64],
    edges: &'a [Edge],
    components: &'a [u32],
}

/// The payload as read.
#[derive(Deserialize)]
struct Payload {
    header: Header,
    nodes: Vec<f64>,
    edges: Vec<Edge>,
    components: Vec<u32>,
}

/// A 64-bit checksum: words of eight bytes folded in by xor, multiplication by an odd constant
/// and rotation. Each step is a bijection of the state for a fixed word, so a change confined
/// to one word (any single flipped byte, any burst of up to eight bytes inside a word) always
/// changes the result; other corruption goes unnoticed with probability about 2⁻⁶⁴.
pub fn checksum(bytes: &[u8]) -> u64 {
    const K: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut h = 0x243f_6a88_85a3_08d3 ^ (bytes.len() as u64).wrapping_mul(K);
    let mut chunks = bytes.chunks_exact(8);
    for c in &mut chunks {
        let w = u64::from_le_bytes(c.try_into().expect("chunks of eight"));
        h = (h ^ w).wrapping_mul(K).rotate_left(31);
    }
    let rest = chunks.remainder();
    if !rest.is_empty() {
        let mut last = [0u8; 8];
        last[..rest.len()].copy_from_slice(rest);
        h = (h ^ u64::from_le_bytes(last))
            .wrapping_mul(K)
            .rotate_left(31);
    }
    // final avalanche (the finaliser of MurmurHash3)
    h ^= h >> 33;
    h = h.wrapping_mul(0xff51_afd7_ed55_8ccd);
    h ^= h >> 33;
    h
}

fn bincode_config() -> bincode::config::Configuration {
    bincode::config::standard()
}

/// Decodes the payload with a byte limit of at least eight times its size (the decoder counts
/// decoded primitives by their size in memory, at most eight bytes per encoded byte), rounded
/// up to a power of eight: a corrupted length cannot make it allocate more than that.
fn decode_payload(payload: &[u8]) -> Result<(Payload, usize), bincode::error::DecodeError> {
    let need = payload.len().saturating_mul(8);
    macro_rules! with_limits {
        ($($shift:literal),*) => {$(
            if need <= (1usize << $shift) {
                return bincode::serde::decode_from_slice(
                    payload,
                    bincode_config().with_limit::<{ 1usize << $shift }>(),
                );
            }
        )*};
    }
    with_limits!(12, 15, 18, 21, 24, 27, 30);
    bincode::serde::decode_from_slice(payload, bincode_config().with_limit::<{ usize::MAX }>())
}

impl Roadmap {
    /// The roadmap file's bytes.
    pub fn to_bytes(&self) -> Result<Vec<u8>, RoadmapError> {
        let payload = bincode::serde::encode_to_vec(
            PayloadRef {
                header: self.header(),
                nodes: self.coords(),
                edges: self.edges(),
                components: self.component_labels(),
            },
            bincode_config(),
        )
        .map_err(|e| RoadmapError::Encode(e.to_string()))?;
        let mut out = Vec::with_capacity(FIXED_HEADER_LEN + payload.len());
        out.extend_from_slice(&MAGIC);
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        out.extend_from_slice(&checksum(&payload).to_le_bytes());
        let header_sum = checksum(&out);
        out.extend_from_slice(&header_sum.to_le_bytes());
        out.extend_from_slice(&payload);
        Ok(out)
    }

    /// A digest of the roadmap's content: the [`checksum`] of its file's bytes. Equal roadmaps
    /// have equal digests; merges order their parts by it, so that the order parts are given
    /// in does not matter.
    pub fn digest(&self) -> Result<u64, RoadmapError> {
        Ok(checksum(&self.to_bytes()?))
    }

    /// Reads a roadmap from its bytes and checks that it was learnt for the scene with
    /// `expected_fingerprint`.
    pub fn from_bytes(bytes: &[u8], expected_fingerprint: u64) -> Result<Roadmap, RoadmapError> {
        let roadmap = Self::from_bytes_any_scene(bytes)?;
        let found = roadmap.header().fingerprint;
        if found != expected_fingerprint {
            return Err(RoadmapError::ForeignScene {
                expected: expected_fingerprint,
                found,
            });
        }
        Ok(roadmap)
    }

    /// Reads a roadmap from its bytes without asking which scene it belongs to (for `info`).
    pub fn from_bytes_any_scene(bytes: &[u8]) -> Result<Roadmap, RoadmapError> {
        let found = bytes.len() as u64;
        let truncated = |needed: u64| RoadmapError::Truncated { found, needed };
        if bytes.len() < MAGIC.len() {
            return Err(if MAGIC.starts_with(bytes) {
                truncated(FIXED_HEADER_LEN as u64)
            } else {
                RoadmapError::NotARoadmap
            });
        }
        if bytes[..8] != MAGIC {
            return Err(RoadmapError::NotARoadmap);
        }
        if bytes.len() < 12 {
            return Err(truncated(FIXED_HEADER_LEN as u64));
        }
        let word = |at: usize| u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8 bytes"));
        let version = u32::from_le_bytes(bytes[8..12].try_into().expect("4 bytes"));
        if version != FORMAT_VERSION {
            return Err(RoadmapError::WrongVersion {
                found: version,
                supported: FORMAT_VERSION,
            });
        }
        if bytes.len() < FIXED_HEADER_LEN {
            return Err(truncated(FIXED_HEADER_LEN as u64));
        }
        if checksum(&bytes[..28]) != word(28) {
            return Err(RoadmapError::Corrupted(
                "the fixed header's checksum does not match".into(),
            ));
        }
        let payload_len = word(12);
        let total = payload_len
            .checked_add(FIXED_HEADER_LEN as u64)
            .ok_or_else(|| RoadmapError::Corrupted("impossible payload length".into()))?;
        if found < total {
            return Err(truncated(total));
        }
        if found > total {
            return Err(RoadmapError::Corrupted(format!(
                "{} unexpected bytes after the end of the roadmap",
                found - total
            )));
        }
        let payload = &bytes[FIXED_HEADER_LEN..];
        if checksum(payload) != word(20) {
            return Err(RoadmapError::Corrupted(
                "the payload's checksum does not match".into(),
            ));
        }
        let (p, used) = decode_payload(payload)
            .map_err(|e| RoadmapError::Corrupted(format!("the payload does not decode: {e}")))?;
        if used != payload.len() {
            return Err(RoadmapError::Corrupted(format!(
                "the payload decodes from {used} of its {} bytes",
                payload.len()
            )));
        }
        check_space(&p.header.space)?;
        p.header
            .params
            .validate()
            .map_err(|e| RoadmapError::Corrupted(format!("learning parameters: {e}")))?;
        check_local_spec(&p.header.local_spec)?;
        let labels = p.components;
        let roadmap =
            Roadmap::assemble(p.header, p.nodes, p.edges).map_err(RoadmapError::Corrupted)?;
        if labels != roadmap.component_labels() {
            return Err(RoadmapError::Corrupted(
                "the component labels do not match the edges".into(),
            ));
        }
        Ok(roadmap)
    }

    /// Saves the roadmap to `path` atomically: the bytes go to a temporary file in the same
    /// directory ([`temp_path`]), which is flushed to disk and then renamed over `path`. If
    /// anything fails, `path` keeps its previous content and the temporary file is removed.
    /// Special files are refused, never replaced ([`write_atomically`]). A roadmap learnt with
    /// a via-point `sidestep` is refused: the file would not record it.
    pub fn save(&self, path: &Path) -> Result<(), RoadmapError> {
        if let LocalSpec::ViaPoint(o) = &self.header().local_spec {
            if o.sidestep.is_some() {
                return Err(RoadmapError::Encode(
                    "the local method's sidestep is not recorded in roadmap files; learn the \
                     roadmap to be saved without it"
                        .into(),
                ));
            }
        }
        let bytes = self.to_bytes()?;
        write_atomically(path, |w| w.write_all(&bytes))
    }

    /// Loads the roadmap at `path` and checks that it was learnt for the scene with
    /// `expected_fingerprint`.
    pub fn load(path: &Path, expected_fingerprint: u64) -> Result<Roadmap, RoadmapError> {
        Self::from_bytes(&read(path)?, expected_fingerprint)
    }

    /// Loads the roadmap at `path` whatever scene it was learnt for (for `info`).
    pub fn load_any_scene(path: &Path) -> Result<Roadmap, RoadmapError> {
        Self::from_bytes_any_scene(&read(path)?)
    }
}

/// The bytes of the roadmap file at `path`, reading at most what its fixed header announces:
/// non-regular files (`/dev/zero`, FIFOs) are refused before they are read, a file whose
/// header is not a roadmap's is read no further than the header, and a file longer than its
/// header announces is refused from its size alone.
fn read(path: &Path) -> Result<Vec<u8>, RoadmapError> {
    let (file, size) = safe_file::open_regular(path).map_err(RoadmapError::from_file)?;
    let io = |source| RoadmapError::Io {
        action: "read",
        path: path.to_path_buf(),
        source,
    };
    let mut file = std::io::BufReader::new(file);
    let mut bytes = Vec::with_capacity(FIXED_HEADER_LEN);
    (&mut file)
        .take(FIXED_HEADER_LEN as u64)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() < FIXED_HEADER_LEN
        || bytes[..8] != MAGIC
        || checksum(&bytes[..28]) != u64::from_le_bytes(bytes[28..36].try_into().expect("8"))
    {
        // from_bytes names what is wrong with the header
        return Ok(bytes);
    }
    let payload_len = u64::from_le_bytes(bytes[12..20].try_into().expect("8 bytes"));
    let total = payload_len.saturating_add(FIXED_HEADER_LEN as u64);
    if size > total {
        return Err(RoadmapError::Corrupted(format!(
            "{} unexpected bytes after the end of the roadmap",
            size - total
        )));
    }
    // at most what the header announces, and never more than the file holds
    bytes.reserve((size.min(total) as usize).saturating_sub(FIXED_HEADER_LEN));
    file.take(payload_len).read_to_end(&mut bytes).map_err(io)?;
    Ok(bytes)
}

/// A local method read from a file must be one the spec-string parser would give
/// ([`LocalSpec::validate`]).
pub(super) fn check_local_spec(spec: &LocalSpec) -> Result<(), RoadmapError> {
    spec.validate()
        .map_err(|reason| RoadmapError::UnknownLocalMethod {
            spec: spec.to_string(),
            reason,
        })
}

/// A space read from a file must be one its constructors accept.
fn check_space(space: &Space) -> Result<(), RoadmapError> {
    let (lower, upper, scale) = (space.lower(), space.upper(), space.rotation_scale());
    let rebuilt = match space.kind() {
        SpaceKind::Euclidean(n) if n == lower.len() => {
            Space::euclidean(lower.to_vec(), upper.to_vec()).map_err(|e| e.to_string())
        }
        SpaceKind::Se2 if lower.len() == 2 && upper.len() == 2 => {
            Space::se2([lower[0], lower[1]], [upper[0], upper[1]], scale).map_err(|e| e.to_string())
        }
        SpaceKind::Se3 if lower.len() == 3 && upper.len() == 3 => Space::se3(
            [lower[0], lower[1], lower[2]],
            [upper[0], upper[1], upper[2]],
            scale,
        )
        .map_err(|e| e.to_string()),
        SpaceKind::Joints { dof, continuous } if dof == lower.len() && dof == upper.len() => {
            let flags: Vec<bool> = (0..dof)
                .map(|i| crate::space::joints::bit(continuous, i))
                .collect();
            Space::joints(lower.to_vec(), upper.to_vec(), &flags).map_err(|e| e.to_string())
        }
        SpaceKind::Se2Bodies(k) if lower.len() == 3 * k && upper.len() == 3 * k => {
            Space::se2_bodies(k, [lower[0], lower[1]], [upper[0], upper[1]], scale)
                .map_err(|e| e.to_string())
        }
        SpaceKind::Se3Bodies(k) if lower.len() == 7 * k && upper.len() == 7 * k => {
            let (lo, hi) = (
                [lower[0], lower[1], lower[2]],
                [upper[0], upper[1], upper[2]],
            );
            Space::se3_bodies(k, lo, hi, scale).map_err(|e| e.to_string())
        }
        _ => Err("bounds of the wrong dimension".into()),
    };
    match rebuilt {
        Ok(s) if s == *space => Ok(()),
        Ok(_) => Err(RoadmapError::Corrupted(
            "the space's rotation scale does not fit its kind".into(),
        )),
        Err(e) => Err(RoadmapError::Corrupted(format!("the space: {e}"))),
    }
}

/// Where [`write_atomically`] puts the bytes for `target` before renaming: a hidden file next
/// to it, named after it, the process and a counter (so concurrent saves do not collide).
pub fn temp_path(target: &Path) -> PathBuf {
    safe_file::temp_path(target)
}

/// Writes a file the way a crash cannot half-do ([`safe_file::write_atomically`]): `write`
/// fills a temporary file in the same directory, which is synced and renamed over `target`.
/// On any error the temporary file is removed and `target` is untouched. A target that is not
/// a regular file (a device, FIFO, directory) is refused, never replaced; a symbolic link is
/// followed; temporaries left by killed saves of the same target are removed.
pub fn write_atomically(
    target: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> Result<(), RoadmapError> {
    safe_file::write_atomically(target, write)
        .map(drop)
        .map_err(RoadmapError::from_file)
}
