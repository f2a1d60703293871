use super::*;

fn spec(a: &[(&str, &str)]) -> JobSpec {
    JobSpec {
        preset: None,
        assignments: a.iter().map(|(k, v)| Assignment::flag(k, v)).collect(),
    }
}

#[test]
fn ranges_exclude_stop_and_keep_the_typed_decimals() {
    let s = Sweep::parse("wind-dir=0:360:45").unwrap();
    assert_eq!(
        s.values,
        ["0", "45", "90", "135", "180", "225", "270", "315"]
    );
    let s = Sweep::parse("time=0:1:0.1").unwrap();
    assert_eq!(s.values.len(), 10, "{:?}", s.values);
    assert_eq!(
        s.values[3], "0.3",
        "i·step, printed with the typed decimals"
    );
    let s = Sweep::parse("wind-speed=10:4:-2").unwrap();
    assert_eq!(s.values, ["10", "8", "6"]);
    assert_eq!(Sweep::parse("height-range=-1:1").unwrap().values, ["-1:1"]);
    for bad in [
        "wind-dir",
        "=1,2",
        "seed=1,,2",
        "wind-dir=0:10:0",
        "wind-dir=0:10:-1",
    ] {
        assert!(Sweep::parse(bad).is_err(), "{bad} must be refused");
    }
}

#[test]
fn the_product_nests_the_sweeps_in_the_order_given() {
    let sweeps = [
        Sweep::parse("wind-dir=0,90").unwrap(),
        Sweep::parse("seed=1:4:1").unwrap(),
    ];
    let jobs = product(&[spec(&[])], &sweeps).unwrap();
    assert_eq!(jobs.len(), 2 * 3);
    let pairs: Vec<(String, String)> = jobs
        .iter()
        .map(|j| {
            (
                j.assignments[0].value.clone(),
                j.assignments[1].value.clone(),
            )
        })
        .collect();
    let expected: Vec<(String, String)> = ["0", "90"]
        .iter()
        .flat_map(|d| {
            ["1", "2", "3"]
                .iter()
                .map(move |s| (d.to_string(), s.to_string()))
        })
        .collect();
    assert_eq!(pairs, expected, "the first sweep is the outer loop");
    let two = product(
        &[spec(&[("seed", "7")]), spec(&[("seed", "8")])],
        &sweeps[..1],
    )
    .unwrap();
    assert_eq!(two.len(), 4, "manifest jobs times the sweep");
    assert_eq!(two[1].assignments[0].value, "7");
    assert_eq!(two[2].assignments[0].value, "8");
}

#[test]
fn names_fill_the_index_and_any_key() {
    let t = NameTemplate::default_for(&["wind.direction_deg".into(), "seed".into()]);
    assert_eq!(t.text, "{index}_wind-dir={wind.direction_deg}_seed={seed}");
    let name = t.render(7, 120, |k| match k {
        "wind.direction_deg" => "22.5".into(),
        _ => "3".into(),
    });
    assert_eq!(name, "007_wind-dir=22.5_seed=3");
    let t = NameTemplate::parse("sea-{wind-speed}/x").err();
    assert!(t.is_some(), "folders are refused");
    let e = NameTemplate::parse("a{wind.sped}").unwrap_err().to_string();
    assert!(e.contains("wind.sped"), "{e}");
    let t = NameTemplate::parse("s{size}").unwrap();
    let p = layers::resolve(None, &[Assignment::flag("size", "64x32")]).unwrap();
    let tree = params_tree(&p).unwrap();
    assert_eq!(t.render(0, 1, |k| value_text(&tree, k).unwrap()), "s64x32");
}

#[test]
fn shards_are_disjoint_and_cover_every_job() {
    for n in 1..6 {
        for job in 0..23 {
            let owners: Vec<usize> = (1..=n).filter(|&k| Shard { k, n }.contains(job)).collect();
            assert_eq!(owners.len(), 1, "job {job} of {n} shards: {owners:?}");
        }
    }
    assert!(Shard::parse("0/3").is_err() && Shard::parse("4/3").is_err());
    assert_eq!(Shard::parse("2/3").unwrap(), Shard { k: 2, n: 3 });
}

#[test]
fn items_are_inclusive_ranges_with_a_step() {
    let i = Items::parse("3-9:3", 10).unwrap();
    let jobs: Vec<usize> = (0..10).filter(|&j| i.contains(j)).collect();
    assert_eq!(jobs, [3, 6, 9], "both ends included");
    assert_eq!(i.to_string(), "3-9:3");
    assert_eq!(Selection::Items(i).index_stem(), "index.items-3-9-by-3");
    let one = Items::parse("4", 10).unwrap();
    assert_eq!((one.first, one.last), (4, 4));
    assert_eq!(Selection::Items(one).index_stem(), "index.items-4-4");
    for bad in ["3-10", "5-4", "1-2:0", "a-b", "-3", "1-2:x"] {
        let e = Items::parse(bad, 10).unwrap_err().to_string();
        assert!(e.contains("--items") && e.contains("< 10"), "{bad}: {e}");
    }
}
