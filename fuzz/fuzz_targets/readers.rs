//! The height-map readers of `analyze` and `render --from` (32-bit float TIFF, 16-bit
//! PNG with its JSON sidecar) and the α weight-map reader: whatever the bytes, a clear
//! one-line error or a grid of finite samples, which the analysis then takes.
//!
//! Input: one selector byte (bit 0: PNG or TIFF name; bit 1: with a sidecar), then the
//! image bytes, then, after the bytes `\n--side--\n`, the sidecar's.
#![no_main]

use std::path::PathBuf;
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;

fn dir() -> &'static PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        // Headers may declare huge images: the readers refuse those beyond this.
        // SAFETY: set once, before any other thread reads the environment.
        unsafe { std::env::set_var(seasynth::limits::MEMORY_ENV, "256M") };
        let d = std::env::temp_dir().join(format!("seasynth-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&d).expect("temporary folder");
        d
    })
}

fn one_line(e: &impl std::fmt::Display) {
    let text = e.to_string();
    assert!(!text.contains('\n'), "error of more than one line: {text}");
}

fuzz_target!(|data: &[u8]| {
    let Some((&selector, rest)) = data.split_first() else {
        return;
    };
    let sep = b"\n--side--\n";
    let (image, side) = match rest.windows(sep.len()).position(|w| w == sep) {
        Some(i) => (&rest[..i], Some(&rest[i + sep.len()..])),
        None => (rest, None),
    };
    let d = dir();
    let path = d.join(if selector & 1 == 0 { "h.png" } else { "h.tif" });
    let side_path = d.join("h.json");
    let _ = std::fs::remove_file(d.join("h.png"));
    let _ = std::fs::remove_file(d.join("h.tif"));
    let _ = std::fs::remove_file(&side_path);
    std::fs::write(&path, image).expect("write the image");
    if let (Some(side), true) = (side, selector & 2 != 0) {
        std::fs::write(&side_path, side).expect("write the sidecar");
    }
    match seasynth::io::load(&path) {
        Ok((grid, sidecar)) => {
            assert!(
                grid.data.iter().all(|v| v.is_finite()),
                "non-finite sample read"
            );
            let target = sidecar
                .as_ref()
                .and_then(|s| seasynth::commands::analyze::target_from_sidecar(s, &grid.spec).ok());
            let a = seasynth::measure::analyze(&grid, target.as_ref());
            let numbers = [a.min_m, a.max_m, a.mean_m, a.std_m, a.hs_m, a.dk_rad_per_m];
            assert!(numbers.iter().all(|v| v.is_finite()), "{a:?}");
            for v in [
                a.peak_k_rad_per_m,
                a.peak_wavelength_m,
                a.peak_direction_deg,
            ] {
                assert!(v.is_none_or(f64::is_finite), "{a:?}");
            }
        }
        Err(e) => one_line(&e),
    }
    match seasynth::field::weight::read_gray(&path) {
        Ok(img) => assert!(img.values.iter().all(|v| (0.0..=1.0).contains(v))),
        Err(e) => one_line(&e),
    }
});
