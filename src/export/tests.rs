//! Tests of the export module: staging, row batches, the extension table, the mapping.

use super::*;

#[test]
fn rows_come_out_in_order_across_batches_and_write_errors_surface() {
    let mut out = Vec::new();
    par_rows(&mut out, 5000, 3, |r, buf| {
        buf.extend_from_slice(format!("{r}\n").as_bytes())
    })
    .unwrap();
    let want: String = (0..5000).map(|r| format!("{r}\n")).collect();
    assert_eq!(String::from_utf8(out).unwrap(), want);
    struct Full;
    impl Write for Full {
        fn write(&mut self, _: &[u8]) -> io::Result<usize> {
            Err(io::Error::other("disk full"))
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }
    let e = par_rows(&mut Full, 100_000, 1000, |_, buf| buf.push(b'x')).unwrap_err();
    assert_eq!(e.to_string(), "disk full");
}

#[test]
fn formats_follow_extensions() {
    assert_eq!(
        Format::from_path(Path::new("a/b.PNG")).unwrap(),
        Format::Png16
    );
    assert_eq!(
        Format::from_path(Path::new("b.tiff")).unwrap(),
        Format::Tiff32
    );
    let e = Format::from_path(Path::new("b.bmp"))
        .unwrap_err()
        .to_string();
    assert!(e.contains(".bmp") && e.contains(".png"), "{e}");
    assert!(Format::from_path(Path::new("noext")).is_err());
}

#[test]
fn mapping_encodes_the_range_ends_and_clamps() {
    let m = HeightMapping {
        min_m: -2.0,
        max_m: 3.0,
    };
    assert_eq!(m.encode(-2.0), 0);
    assert_eq!(m.encode(3.0), 65535);
    assert_eq!(m.encode(-5.0), 0);
    assert_eq!(m.encode(9.0), 65535);
    assert!((m.decode(m.encode(0.5)) - 0.5).abs() <= m.step_m() / 2.0 + 1e-12);
    assert_eq!(
        HeightMapping {
            min_m: 1.0,
            max_m: 1.0
        }
        .encode(1.0),
        0
    );
}

#[test]
fn the_scalar_and_vector_encoders_give_the_documented_mappings_bytes_on_every_isa() {
    // Heights at and next to every half step of a mapping, past both ends, and the
    // non-finite ones, for a usual range, a tiny one and the flat and NaN spans.
    let m = HeightMapping {
        min_m: -1.7,
        max_m: 2.3,
    };
    let mut hs: Vec<f32> = vec![f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -0.0, 0.0];
    hs.extend([
        -1e30,
        1e30,
        -1.7,
        2.3,
        -1.7f32.next_down(),
        2.3f32.next_up(),
    ]);
    for k in 0..=65535u32 {
        let h = (m.min_m + (k as f64 + 0.5) * m.step_m()) as f32;
        hs.extend([h, h.next_down(), h.next_up()]);
    }
    hs.extend((0..10_007).map(|i| (i as f32 * 7.31e-4).sin() * 3.0));
    let mappings = [
        m,
        HeightMapping {
            min_m: 0.25,
            max_m: 0.25 + 1e-6,
        },
        HeightMapping {
            min_m: 1.0,
            max_m: 1.0,
        },
        HeightMapping {
            min_m: 0.0,
            max_m: f64::NAN,
        },
    ];
    for m in mappings {
        // The documented mapping with the library's round, and `encode` itself.
        let span = m.max_m - m.min_m;
        let lib = |h: f32| {
            let v = (h as f64 - m.min_m) / span * 65535.0;
            if span.is_nan() || span <= 0.0 || v.is_nan() {
                0
            } else {
                v.clamp(0.0, 65535.0).round() as u16
            }
        };
        let want: Vec<u8> = hs.iter().flat_map(|&h| lib(h).to_be_bytes()).collect();
        let scalar: Vec<u8> = hs.iter().flat_map(|&h| m.encode(h).to_be_bytes()).collect();
        assert!(
            scalar == want,
            "{m:?}: encode differs from the documented mapping"
        );
        for isa in crate::simd::Isa::available() {
            let mut got = vec![0xAAu8; 2 * hs.len()];
            m.encode_be_on(isa, &hs, &mut got);
            let first = got.iter().zip(&want).position(|(a, b)| a != b);
            assert!(first.is_none(), "{m:?} on {isa:?}: byte {first:?} differs");
        }
    }
}

#[test]
fn a_failed_write_leaves_no_file_and_keeps_an_earlier_one() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("x.png");
    std::fs::write(&target, b"earlier").unwrap();
    let staged = Staged::create(&target).unwrap();
    let r = staged.write_with(|w| {
        w.write_all(b"half")?;
        Err(std::io::Error::other("disk full"))
    });
    assert!(r.is_err());
    assert_eq!(std::fs::read(&target).unwrap(), b"earlier");
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(left.len(), 1, "temporary file removed");
}

#[test]
fn a_staged_file_is_listed_for_cleanup_until_written_or_dropped() {
    let dir = tempfile::tempdir().unwrap();
    let ours = || {
        live::live_files()
            .iter()
            .filter(|f| f.starts_with(dir.path()))
            .count()
    };
    let a = Staged::create(&dir.path().join("a.png")).unwrap();
    let b = Staged::create(&dir.path().join("b.png")).unwrap();
    assert_eq!(ours(), 2, "both temporary files are listed");
    a.write_with(|w| w.write_all(b"a")).unwrap();
    drop(b);
    assert_eq!(ours(), 0, "renamed and dropped files leave the list");
    let names: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(names, vec![std::ffi::OsString::from("a.png")]);
}

#[test]
fn a_missing_folder_is_created_and_a_file_in_the_way_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("a/b/x.png");
    Staged::create(&target)
        .unwrap()
        .write_with(|w| w.write_all(b"x"))
        .unwrap();
    assert_eq!(std::fs::read(&target).unwrap(), b"x");
    // A file where a folder should be: the error names the user's path and that file,
    // never a temporary name.
    let file = dir.path().join("f");
    std::fs::write(&file, b"").unwrap();
    let target = file.join("sub/x.png");
    let e = Staged::create(&target).err().unwrap().to_string();
    assert!(
        e.starts_with(&format!("output {}: ", target.display()))
            && e.contains(&format!("{} is a file, not a folder", file.display())),
        "{e}"
    );
    assert!(!e.contains(".part"), "{e}");
}

#[test]
fn a_checked_file_names_the_allowed_extensions_and_refuses_an_input() {
    let dir = tempfile::tempdir().unwrap();
    let plots = Allowed {
        what: "plots are PNG images",
        extensions: &["png"],
    };
    let e = Staged::create_checked(&dir.path().join("p.jpg"), &plots, &[])
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("plots are PNG images: the file name must end in .png"),
        "{e}"
    );
    let input = dir.path().join("in.png");
    std::fs::write(&input, b"x").unwrap();
    let e = Staged::create_checked(&input, &plots, &[(&input, "is the file being analyzed")])
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("is the file being analyzed"), "{e}");
    assert!(Staged::create_checked(&dir.path().join("p.PNG"), &plots, &[(&input, "")]).is_ok());
}
