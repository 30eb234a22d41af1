//! The roadmap file: round trips, and every kind of bad file rejected with its own error,
//! never a panic; saves that fail leave the previous file intact.

use crate::roadmap_support;

use roadmap_support::*;
use std::path::PathBuf;
use viaroad::local::LocalSpec;
use viaroad::roadmap::persist::{checksum, temp_path, write_atomically, FIXED_HEADER_LEN};
use viaroad::roadmap::{LearnParams, QueryPlanner, Roadmap, RoadmapError, FORMAT_VERSION, MAGIC};
use viaroad::scene::Scene;

fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("roadmap_persist_{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn sample(feedback: bool, nodes: usize) -> (Scene, Roadmap) {
    let scene = disc_scene(31, 30, 0.06);
    let params = LearnParams {
        feedback,
        ..LearnParams::default()
    };
    let roadmap = learn(&scene, &LocalSpec::default(), &params, nodes, 2).roadmap;
    (scene, roadmap)
}

/// Rewrites the fixed header's checksums after the payload was edited, so that the edit gets
/// past the checksums and reaches the decoder.
fn reseal(bytes: &mut [u8]) {
    let payload_len = (bytes.len() - FIXED_HEADER_LEN) as u64;
    bytes[12..20].copy_from_slice(&payload_len.to_le_bytes());
    let sum = checksum(&bytes[FIXED_HEADER_LEN..]);
    bytes[20..28].copy_from_slice(&sum.to_le_bytes());
    let head = checksum(&bytes[..28]);
    bytes[28..36].copy_from_slice(&head.to_le_bytes());
}

#[test]
fn save_load_gives_the_same_roadmap_and_the_same_answers() {
    for feedback in [true, false] {
        let (scene, roadmap) = sample(feedback, 600);
        let dir = scratch_dir(&format!("round_trip_{feedback}"));
        let path = dir.join("discs.bin");
        roadmap.save(&path).unwrap();
        let loaded = Roadmap::load(&path, scene.fingerprint()).unwrap();
        assert_eq!(loaded.to_bytes().unwrap(), std::fs::read(&path).unwrap());
        assert_eq!(loaded.header(), roadmap.header());
        assert_eq!(loaded.coords(), roadmap.coords());
        assert_eq!(loaded.edges(), roadmap.edges());
        assert_eq!(loaded.component_labels(), roadmap.component_labels());
        assert_eq!(loaded.info(), roadmap.info());
        let oracle = scene.oracle();
        let before = QueryPlanner::new(&roadmap, oracle.as_ref()).unwrap();
        let after = QueryPlanner::new(&loaded, oracle.as_ref()).unwrap();
        for (s, g) in random_queries(&scene, 40, 8) {
            assert_eq!(before.query(&s, &g), after.query(&s, &g));
        }
        // no temporary file is left next to it
        let names: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("discs.bin")]);
    }
}

#[test]
fn truncated_files_are_reported_as_truncated_at_every_offset() {
    let (scene, roadmap) = sample(true, 120);
    let bytes = roadmap.to_bytes().unwrap();
    let n = bytes.len();
    let mut offsets: Vec<usize> = (0..=FIXED_HEADER_LEN + 8).collect();
    offsets.extend((FIXED_HEADER_LEN..n).step_by(7));
    offsets.push(n - 1);
    for cut in offsets {
        match Roadmap::from_bytes(&bytes[..cut], scene.fingerprint()) {
            Err(RoadmapError::Truncated { found, needed }) => {
                assert_eq!(found, cut as u64);
                assert!(needed > found, "cut {cut}: needed {needed}");
            }
            other => panic!("cut at {cut} of {n}: {other:?}"),
        }
    }
}

/// One flipped byte anywhere: the magic → not a roadmap, the version → wrong version, anything
/// else → corrupted (a checksum catches it before decoding).
#[test]
fn a_flipped_byte_anywhere_is_caught() {
    let (scene, roadmap) = sample(false, 150);
    let bytes = roadmap.to_bytes().unwrap();
    let mut offsets: Vec<usize> = (0..FIXED_HEADER_LEN + 16).collect();
    offsets.extend((FIXED_HEADER_LEN..bytes.len()).step_by(5));
    offsets.push(bytes.len() - 1);
    for at in offsets {
        for mask in [0x01u8, 0x80, 0xff] {
            let mut bad = bytes.clone();
            bad[at] ^= mask;
            let r = Roadmap::from_bytes(&bad, scene.fingerprint());
            match at {
                0..8 => assert!(matches!(r, Err(RoadmapError::NotARoadmap)), "{at}: {r:?}"),
                8..12 => assert!(
                    matches!(r, Err(RoadmapError::WrongVersion { .. })),
                    "{at}: {r:?}"
                ),
                _ => assert!(matches!(r, Err(RoadmapError::Corrupted(_))), "{at}: {r:?}"),
            }
        }
    }
}

/// Edited payloads that pass the checksums still never panic: they decode to an error, or to a
/// roadmap whose bytes are the edited bytes.
#[test]
fn resealed_garbage_never_panics() {
    let (scene, roadmap) = sample(false, 80);
    let bytes = roadmap.to_bytes().unwrap();
    let mut state = 0x1234_5678_9abc_def0u64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        state
    };
    let mut errors = 0;
    for _ in 0..400 {
        let mut bad = bytes.clone();
        for _ in 0..1 + next() % 3 {
            let at = FIXED_HEADER_LEN + (next() as usize) % (bad.len() - FIXED_HEADER_LEN);
            bad[at] = next() as u8;
        }
        reseal(&mut bad);
        match Roadmap::from_bytes_any_scene(&bad) {
            Ok(r) => assert_eq!(r.to_bytes().unwrap(), bad),
            Err(RoadmapError::Corrupted(_) | RoadmapError::UnknownLocalMethod { .. }) => {
                errors += 1
            }
            Err(e) => panic!("unexpected error {e}"),
        }
    }
    // most of the payload is floating-point coordinates, where any byte decodes; the floor only
    // makes sure the error paths are exercised (the share depends on the roadmap's layout)
    assert!(errors > 40, "only {errors} of 400 edits were rejected");
    let _ = scene;
}

/// A length prefix edited to a huge value is refused instead of allocating it: the decoder's
/// byte limit stops it, or (for a sequence of numbers, which serde pre-allocates only
/// cautiously) the payload's end does.
#[test]
fn a_huge_length_prefix_is_refused() {
    let (_, roadmap) = sample(true, 50);
    let bytes = roadmap.to_bytes().unwrap();
    let coords = roadmap.coords();
    let first = coords[0].to_le_bytes();
    let at = bytes
        .windows(8)
        .position(|w| w == first)
        .expect("the node coordinates are stored verbatim");
    // bincode 2's varint length in front of them: one byte below 251, else the marker 251 and
    // a u16 (a few hundred coordinates)
    let prefix = if coords.len() < 251 { at - 1 } else { at - 3 };
    let stored = match bytes[prefix] {
        251 => u64::from(u16::from_le_bytes([bytes[at - 2], bytes[at - 1]])),
        n => u64::from(n),
    };
    assert_eq!(
        stored,
        coords.len() as u64,
        "found the nodes' length prefix"
    );
    let mut bad = bytes.clone();
    // the length prefix becomes "a u64 follows": the next eight bytes, a huge number
    bad[prefix] = 253;
    reseal(&mut bad);
    match Roadmap::from_bytes_any_scene(&bad) {
        Err(RoadmapError::Corrupted(why)) => assert!(
            why.contains("LimitExceeded") || why.contains("UnexpectedEnd"),
            "{why}"
        ),
        other => panic!("{other:?}"),
    }
}

/// A roadmap saved by the build before the typed local method (format version 2, the spec
/// stored as a string) gets the clear "other format version" error, not a decoding error.
#[test]
fn a_version_2_file_is_refused_with_a_clear_error() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::load(&root.join("scenes/discs-example.toml")).unwrap();
    let path = root.join("tests/data/roadmaps/discs-example-v2.bin");
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(bytes[..8], MAGIC);
    assert_eq!(bytes[8..12], 2u32.to_le_bytes(), "a genuine version-2 file");
    match Roadmap::load(&path, scene.fingerprint()) {
        Err(
            e @ RoadmapError::WrongVersion {
                found: 2,
                supported,
            },
        ) => {
            assert_eq!(supported, FORMAT_VERSION);
            const { assert!(FORMAT_VERSION > 2) };
            let msg = e.to_string();
            assert!(
                msg.contains("version 2") && msg.contains(&format!("version {FORMAT_VERSION}")),
                "{msg}"
            );
        }
        other => panic!("expected WrongVersion, got {other:?}"),
    }
}

/// A header whose local method is out of range (as only an edited file can hold) is refused
/// on load with [`RoadmapError::UnknownLocalMethod`], as the spec-string parser would refuse it.
#[test]
fn an_out_of_range_local_method_is_refused() {
    let scene = disc_scene(31, 30, 0.06);
    let resolution = 0.012_345_678_9f64;
    let spec = LocalSpec::Sampled { resolution };
    let roadmap = learn(&scene, &spec, &LearnParams::default(), 30, 1).roadmap;
    assert_eq!(roadmap.header().local_spec, spec);
    let bytes = roadmap.to_bytes().unwrap();
    let at = bytes
        .windows(8)
        .position(|w| w == resolution.to_le_bytes())
        .expect("the resolution is stored verbatim");
    for (bad_resolution, why) in [(-1.0f64, "positive"), (1e-300, "smallest resolution")] {
        let mut bad = bytes.clone();
        bad[at..at + 8].copy_from_slice(&bad_resolution.to_le_bytes());
        reseal(&mut bad);
        match Roadmap::from_bytes(&bad, scene.fingerprint()) {
            Err(e @ RoadmapError::UnknownLocalMethod { .. }) => {
                assert!(e.to_string().contains(why), "{e}");
            }
            other => panic!("{other:?}"),
        }
    }
}

#[test]
fn other_files_versions_and_scenes_have_their_own_errors() {
    let (scene, roadmap) = sample(true, 100);
    let bytes = roadmap.to_bytes().unwrap();
    // not a roadmap
    for junk in [
        &b"name = \"discs\"\n[space]\n"[..],
        b"\x89PNG\r\n\x1a\n0000000000",
        b"VIAROAD",
    ] {
        let r = Roadmap::from_bytes(junk, scene.fingerprint());
        if MAGIC.starts_with(junk) {
            assert!(matches!(r, Err(RoadmapError::Truncated { .. })));
        } else {
            assert!(matches!(r, Err(RoadmapError::NotARoadmap)), "{r:?}");
        }
    }
    // another version, properly sealed
    let mut v2 = bytes.clone();
    v2[8..12].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
    reseal(&mut v2);
    match Roadmap::from_bytes(&v2, scene.fingerprint()) {
        Err(RoadmapError::WrongVersion { found, supported }) => {
            assert_eq!((found, supported), (FORMAT_VERSION + 1, FORMAT_VERSION));
        }
        other => panic!("{other:?}"),
    }
    // another scene
    let other = disc_scene(32, 30, 0.06);
    match Roadmap::from_bytes(&bytes, other.fingerprint()) {
        Err(RoadmapError::ForeignScene { expected, found }) => {
            assert_eq!(expected, other.fingerprint());
            assert_eq!(found, scene.fingerprint());
        }
        other => panic!("{other:?}"),
    }
    // but `info` reads it whatever the scene
    assert!(Roadmap::from_bytes_any_scene(&bytes).is_ok());
    // bytes after the end
    let mut longer = bytes.clone();
    longer.push(0);
    assert!(matches!(
        Roadmap::from_bytes(&longer, scene.fingerprint()),
        Err(RoadmapError::Corrupted(_))
    ));
    // a missing file
    let missing = scratch_dir("missing").join("none.bin");
    assert!(matches!(
        Roadmap::load(&missing, scene.fingerprint()),
        Err(RoadmapError::Io { action: "read", .. })
    ));
    // error messages name the problem
    let msg = Roadmap::from_bytes(&bytes[..100], scene.fingerprint())
        .unwrap_err()
        .to_string();
    assert!(msg.contains("truncated"), "{msg}");
}

/// Failed saves leave what was there before, and no temporary file.
#[test]
fn a_failed_save_leaves_the_previous_file_intact() {
    let (_, old) = sample(true, 60);
    let (_, new) = sample(false, 90);
    let dir = scratch_dir("failed_save");
    let path = dir.join("map.bin");
    old.save(&path).unwrap();
    let before = std::fs::read(&path).unwrap();
    let listing = || {
        let mut v: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        v.sort();
        v
    };

    // a writer that fails half-way (a full disk, a crash): nothing replaces the old file
    let bytes = new.to_bytes().unwrap();
    let r = write_atomically(&path, |w| {
        w.write_all(&bytes[..bytes.len() / 2])?;
        Err(std::io::Error::other("disk full"))
    });
    assert!(
        matches!(
            r,
            Err(RoadmapError::Io {
                action: "write",
                ..
            })
        ),
        "{r:?}"
    );
    assert_eq!(std::fs::read(&path).unwrap(), before);
    assert_eq!(listing(), vec![std::ffi::OsString::from("map.bin")]);

    // the target is a directory (with content): refused, the directory stays
    let target_dir = dir.join("taken.bin");
    std::fs::create_dir(&target_dir).unwrap();
    std::fs::write(target_dir.join("keep"), b"keep").unwrap();
    let r = new.save(&target_dir);
    assert!(matches!(r, Err(RoadmapError::File(_))), "{r:?}");
    assert_eq!(std::fs::read(target_dir.join("keep")).unwrap(), b"keep");
    assert_eq!(
        listing(),
        vec![std::ffi::OsString::from("map.bin"), "taken.bin".into()]
    );

    // the directory does not exist
    assert!(new.save(&dir.join("no").join("such.bin")).is_err());

    // a read-only directory (only meaningful where permissions bind: not for root)
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o555)).unwrap();
        let probe = dir.join("probe");
        let binding = std::fs::write(&probe, b"x").is_err();
        if binding {
            let r = new.save(&path);
            assert!(
                matches!(
                    r,
                    Err(RoadmapError::Io {
                        action: "create",
                        ..
                    })
                ),
                "{r:?}"
            );
            assert_eq!(std::fs::read(&path).unwrap(), before);
        } else {
            let _ = std::fs::remove_file(&probe);
            eprintln!("running as a user who may write to read-only directories: skipped");
        }
        std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o755)).unwrap();
    }

    // and a successful save replaces the file
    new.save(&path).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), new.to_bytes().unwrap());
    assert!(temp_path(&path).starts_with(&dir));
}
