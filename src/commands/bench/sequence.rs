//! `bench --sequence`: whole 48-frame `animate` runs beside Blender's ocean bake.

use super::*;

/// Frames of the sequence rows.
const SEQUENCE_FRAMES: usize = 48;

/// Blender's ocean bake of [`sequences`] (`contrib/blender/ocean_bake.py`).
const BLENDER_BAKE: &str = include_str!("../../../contrib/blender/ocean_bake.py");

/// CPU time of the finished child processes (user + system), so far.
pub(super) fn children_cpu_time() -> Duration {
    // SAFETY: getrusage writes the struct it is given and nothing else.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    let rc = unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut u) };
    assert_eq!(rc, 0, "RUSAGE_CHILDREN exists on Linux");
    let t = |v: libc::timeval| Duration::new(v.tv_sec as u64, v.tv_usec as u32 * 1000);
    t(u.ru_utime) + t(u.ru_stime)
}

/// Runs `cmd` to the end: its wall time and the CPU time of its processes.
pub(super) fn run_timed(cmd: &mut std::process::Command) -> Result<(Duration, Duration)> {
    let (t, c) = (Instant::now(), children_cpu_time());
    let out = cmd.output().context("cannot start the timed command")?;
    let wall = t.elapsed();
    if !out.status.success() {
        anyhow::bail!(
            "timed command failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    Ok((wall, children_cpu_time().saturating_sub(c)))
}

/// Times 48-frame `animate` sequences at 1024² (PM 15 m/s over 1024 m, `--method fft`),
/// each a whole run of this executable (start-up, draws and sidecar included), as
/// milliseconds per frame of wall and of CPU time: choppy λ = 1 displacement + foam, the
/// displacement as half-float ZIP EXR with foam in A (Blender's bake format), and a still
/// sea's height PNG + normal + foam. When `blender` runs, its ocean bake of the same sea
/// (resolution 32, 1024², PM 15 m/s, choppiness 1, foam, frames 1–48) is timed from its
/// first file to its last, and the ratio Blender ÷ seasynth per frame is printed.
pub(super) fn sequences(dir: &std::path::Path, threads: Option<usize>) -> Result<()> {
    let frames = SEQUENCE_FRAMES;
    let exe = std::env::current_exe().context("cannot find this executable")?;
    let base = dir.join("sequence");
    let field = [
        "--method",
        "fft",
        "--spectrum",
        "pierson-moskowitz",
        "--wind-speed",
        "15",
        "--size",
        "1024",
        "--extent",
        "1024",
    ];
    let rows: [(&str, &[&str]); 3] = [
        (
            "choppy λ=1, disp + foam",
            &["--choppiness", "1", "--format", "disp,foam"],
        ),
        (
            "choppy λ=1, disp.exr half ZIP",
            &[
                "--choppiness",
                "1",
                "--format",
                "disp.exr",
                "--exr-half",
                "--exr-compression",
                "zip",
            ],
        ),
        (
            "still, png + normal + foam",
            &["--format", "png,normal,foam"],
        ),
    ];
    println!(
        "\nsequences, {frames} frames of 1024² (PM 15 m/s over 1024 m), whole runs: ms per frame"
    );
    println!("  {:<32} {:>8} {:>8}", "animate", "wall", "CPU");
    let per_frame = |d: Duration| d.as_secs_f64() * 1e3 / frames as f64;
    let mut walls = Vec::new();
    for (i, (name, extra)) in rows.iter().enumerate() {
        let out = base.join(format!("s{i}"));
        let mut cmd = std::process::Command::new(&exe);
        cmd.arg("animate")
            .args(field)
            .args(*extra)
            .args(["--frames", &frames.to_string(), "-q", "-o"])
            .arg(&out);
        if let Some(t) = threads {
            cmd.args(["--threads", &t.to_string()]);
        }
        let (wall, cpu) = run_timed(&mut cmd)?;
        println!(
            "  {:<32} {:>8.1} {:>8.1}",
            name,
            per_frame(wall),
            per_frame(cpu)
        );
        walls.push(per_frame(wall));
        std::fs::remove_dir_all(&out).ok();
    }
    let blender = std::process::Command::new("blender")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if !blender {
        println!(
            "  note: blender is not on the PATH: its ocean bake is not timed beside these rows"
        );
        return Ok(());
    }
    let script = base.join("ocean_bake.py");
    let out = base.join("blender");
    std::fs::create_dir_all(&out)?;
    std::fs::write(&script, BLENDER_BAKE)?;
    let mut cmd = std::process::Command::new("blender");
    cmd.args(["-b", "--factory-startup", "--python"])
        .arg(&script)
        .arg("--")
        .arg(format!("{}/", out.display()))
        .arg(frames.to_string());
    run_timed(&mut cmd)?;
    // From the first file to the last: Blender's start-up and scene set-up left out.
    let mut times = Vec::new();
    for e in std::fs::read_dir(&out)? {
        times.push(e?.metadata()?.modified()?);
    }
    let (first, last) = (times.iter().min(), times.iter().max());
    let span = match (first, last) {
        (Some(a), Some(b)) if times.len() >= 2 * frames => b.duration_since(*a)?,
        _ => anyhow::bail!(
            "Blender's bake wrote {} files, not {}",
            times.len(),
            2 * frames
        ),
    };
    let blender_frame = span.as_secs_f64() * 1e3 / (frames - 1) as f64;
    println!(
        "  {:<32} {:>8.1}          Blender ÷ seasynth per frame (wall): disp + foam {:.1}, disp.exr half ZIP {:.1}",
        "Blender 3.x ocean bake, 1st→last",
        blender_frame,
        blender_frame / walls[0],
        blender_frame / walls[1]
    );
    std::fs::remove_dir_all(&out).ok();
    std::fs::remove_file(&script).ok();
    Ok(())
}
