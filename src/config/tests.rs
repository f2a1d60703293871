use super::*;

#[test]
fn defaults_are_valid_and_round_trip_through_toml_and_json() {
    let p = Params::default();
    p.validate().unwrap();
    let t = toml::to_string(&p).unwrap();
    assert_eq!(toml::from_str::<Params>(&t).unwrap(), p, "TOML:\n{t}");
    let j = serde_json::to_string(&p).unwrap();
    assert_eq!(serde_json::from_str::<Params>(&j).unwrap(), p);
}

#[test]
fn several_spellings_of_sizes_extents_ranges_and_beta() {
    let p: Params = toml::from_str(
        "[grid]\nsize = \"256x128\"\nextent_m = 1000\n[output]\nheight_range = \"-2:3.5\"\n[blend]\nbeta = 0.4",
    )
    .unwrap();
    assert_eq!(p.grid.size, Size2([256, 128]));
    assert_eq!(p.grid.extent_m, Extent2([1000.0, 1000.0]));
    assert_eq!(p.output.height_range, Some(Range2([-2.0, 3.5])));
    assert_eq!(p.blend.beta, Beta::Meters(0.4));
    let q: Params =
        toml::from_str("[grid]\nsize = 64\nextent_m = [10.5, 20]\n[blend]\nbeta = \"matched\"")
            .unwrap();
    assert_eq!(q.grid.size, Size2([64, 64]));
    assert_eq!(q.grid.extent_m, Extent2([10.5, 20.0]));
    assert_eq!(q.blend.beta, Beta::Matched);
}

#[test]
fn unknown_keys_are_rejected_with_their_line() {
    let e = toml::from_str::<Params>("seed = 3\n\n[wind]\nsped_mps = 3\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("sped_mps"), "{e}");
    assert!(e.contains("line 4"), "{e}");
    let e = toml::from_str::<Params>(
        "[blend.alpha]\nkind = \"ramp\"\naxis = \"y\"\npower = 3\nfoo = 1\n",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("foo"), "{e}");
}

#[test]
fn validation_names_the_parameter_and_the_allowed_range() {
    let mut p = Params::default();
    p.wind.speed_mps = -3.0;
    let e = p.validate().unwrap_err().to_string();
    assert_eq!(
        e,
        "--wind-speed (wind.speed_mps) must be > 0 and ≤ 100 m/s (got -3)"
    );
    let mut p = Params::default();
    p.grid.size = Size2([0, 16]);
    assert!(
        p.validate()
            .unwrap_err()
            .to_string()
            .contains("between 2 and")
    );
    let mut p = Params::default();
    p.perlin.persistence = 1.0;
    assert!(
        p.validate()
            .unwrap_err()
            .to_string()
            .starts_with("perlin.persistence")
    );
    let p = Params {
        time_s: f64::NAN,
        ..Params::default()
    };
    assert!(p.validate().is_err());
    let mut p = Params::default();
    p.output.height_range = Some(Range2([1.0, -1.0]));
    assert!(p.validate().is_err());
}
