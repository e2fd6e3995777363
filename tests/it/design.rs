//! `biscara design`: the sweep's CSV against `biscara workspace`, --best against the CSV, shards
//! against the whole sweep, the atlas, and bad input.

use crate::golden::check_golden;
use crate::util::{biscara, temp_dir};

/// The data rows of a design CSV, split into fields.
fn rows(text: &str) -> Vec<Vec<String>> {
    text.lines().skip(1).map(|line| line.split(',').map(str::to_owned).collect()).collect()
}

fn number(field: &str) -> f64 {
    field.parse().unwrap_or_else(|_| panic!("not a number: {field}"))
}

const SWEEP: &[&str] =
    &["design", "--l1", "170:250:3", "--l2", "230:310:3", "--base", "120:280:3", "--step", "10"];

#[test]
fn the_default_robots_row_is_what_workspace_says() {
    let dir = temp_dir("design-default");
    let args = ["design", "--l1", "210:210:1", "--l2", "270:270:1", "--base", "200:200:1"];
    let run = biscara(&dir, &[&args[..], &["--step", "4"]].concat());
    run.success();
    let rows = rows(&run.stdout);
    assert_eq!(rows.len(), 1, "{run}");
    let workspace = biscara(&dir, &["workspace", "--step", "4", "--json"]);
    let json: serde_json::Value = serde_json::from_str(&workspace.success().stdout).unwrap();
    let row = &rows[0];
    assert_eq!(&row[..4], ["0", "210", "270", "200"]);
    assert_eq!(number(&row[4]), json["area_mm2"].as_f64().unwrap());
    let min = &json["rectangle"]["min"];
    let max = &json["rectangle"]["max"];
    let (x0, y0) = (min[0].as_f64().unwrap(), min[1].as_f64().unwrap());
    let (x1, y1) = (max[0].as_f64().unwrap(), max[1].as_f64().unwrap());
    assert_eq!([number(&row[5]), number(&row[6])], [x1 - x0, y1 - y0]);
    assert_eq!([number(&row[7]), number(&row[8])], [x0, y0]);
    let (gci, lci_min) = (number(&row[9]), number(&row[10]));
    assert!(0.0 < lci_min && lci_min <= gci && gci < 1.0, "{row:?}");
    assert_eq!(row[11], "ok");
}

#[test]
fn best_is_the_csvs_maximum_for_each_objective() {
    let dir = temp_dir("design-best");
    for (objective, value) in [("rect", None), ("gci", Some(9)), ("lci-min", Some(10))] {
        let run = biscara(
            &dir,
            &[SWEEP, &["--objective", objective, "--best", "best.json", "-o", "d.csv"]].concat(),
        );
        run.success().stderr_has("27 designs evaluated");
        let text = std::fs::read_to_string(dir.join("d.csv")).unwrap();
        let rows = rows(&text);
        assert_eq!(rows.len(), 27);
        let key = |row: &Vec<String>| match value {
            None => number(&row[5]) * number(&row[6]),
            Some(column) => number(&row[column]),
        };
        let eligible = rows.iter().filter(|row| row[11] == "ok");
        let max = eligible.clone().map(key).fold(f64::NEG_INFINITY, f64::max);
        let first = eligible.clone().find(|row| key(row) == max).expect("a maximum");
        let robot: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("best.json")).unwrap()).unwrap();
        assert_eq!(robot["links"]["l1"].as_f64(), Some(number(&first[1])), "{objective}");
        assert_eq!(robot["links"]["l2"].as_f64(), Some(number(&first[2])), "{objective}");
        assert_eq!(robot["base"]["b1x"].as_f64(), Some(number(&first[3]) / 2.0), "{objective}");
        assert_eq!(robot["base"]["b2x"].as_f64(), Some(-number(&first[3]) / 2.0), "{objective}");
        // The robot file works: its workspace has the row's rectangle.
        let ws = biscara(&dir, &["--robot", "best.json", "workspace", "--step", "10", "--json"]);
        let json: serde_json::Value = serde_json::from_str(&ws.success().stdout).unwrap();
        assert_eq!(json["area_mm2"].as_f64(), Some(number(&first[4])));
    }
}

#[test]
fn shards_merge_to_the_whole_sweep_on_any_thread_count() {
    let dir = temp_dir("design-shards");
    biscara(&dir, &[SWEEP, &["-o", "whole.csv", "--threads", "1"]].concat()).success();
    let whole = std::fs::read_to_string(dir.join("whole.csv")).unwrap();
    for k in 1..=4 {
        let shard = format!("{k}/4");
        let out = format!("part{k}.csv");
        biscara(&dir, &[SWEEP, &["--shard", &shard, "-o", &out, "--threads", "2"]].concat())
            .success();
    }
    let run = biscara(
        &dir,
        &["design", "merge", "part3.csv", "part1.csv", "part4.csv", "part2.csv", "-o", "m.csv"],
    );
    run.success().stderr_has("27 designs merged");
    assert_eq!(std::fs::read_to_string(dir.join("m.csv")).unwrap(), whole);
    // A shard left out, or given twice: an error and no output.
    biscara(&dir, &["design", "merge", "part1.csv", "part3.csv", "part4.csv", "-o", "bad.csv"])
        .expect_code(1)
        .stderr_has("design 1 is in none of the files");
    biscara(&dir, &["design", "merge", "part1.csv", "part2.csv", "part2.csv", "-o", "bad.csv"])
        .expect_code(1)
        .stderr_has("part2.csv:2: design 1 is in another file too");
    assert!(!dir.join("bad.csv").exists());
}

#[test]
fn a_task_constrains_the_choice_and_the_pareto_front_and_atlas_are_written() {
    let dir = temp_dir("design-task");
    let run = biscara(
        &dir,
        &[
            SWEEP,
            &["--task", "-200,380,200,420", "--best", "best.json", "--pareto", "front.csv"],
            &["--atlas", "atlas.svg", "-o", "d.csv"],
        ]
        .concat(),
    );
    run.success();
    let text = std::fs::read_to_string(dir.join("d.csv")).unwrap();
    assert!(text.starts_with("index,l1,l2,base,area_mm2,rect_w_mm,rect_h_mm,"));
    assert!(text.lines().next().unwrap().ends_with(",status,task_ok"));
    let rows = rows(&text);
    assert!(rows.iter().any(|r| r[12] == "0") && rows.iter().any(|r| r[12] == "1"), "{text}");
    let robot: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("best.json")).unwrap()).unwrap();
    let chosen = rows
        .iter()
        .find(|r| {
            Some(number(&r[1])) == robot["links"]["l1"].as_f64()
                && Some(number(&r[2])) == robot["links"]["l2"].as_f64()
                && Some(number(&r[3]) / 2.0) == robot["base"]["b1x"].as_f64()
        })
        .expect("the chosen design is a row");
    assert_eq!(chosen[12], "1", "the chosen design covers the task");
    // The front: no row beats a front row in both rectangle area and GCI.
    let front = rows_of(&dir.join("front.csv"));
    assert!(!front.is_empty());
    for f in &front {
        let (area, gci) = (number(&f[5]) * number(&f[6]), number(&f[9]));
        assert!(!rows.iter().filter(|r| r[11] == "ok" && r[12] == "1").any(|r| {
            let (a, g) = (number(&r[5]) * number(&r[6]), number(&r[9]));
            a >= area && g >= gci && (a > area || g > gci)
        }));
    }
    let svg = std::fs::read_to_string(dir.join("atlas.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("base 120 mm") && svg.contains("base 280 mm"));
    // The atlas subcommand draws the same from the CSV.
    biscara(&dir, &["design", "atlas", "d.csv", "--index", "rect", "-o", "a.png"]).success();
    assert_eq!(&std::fs::read(dir.join("a.png")).unwrap()[1..4], b"PNG");
}

#[test]
fn programs_are_timed_as_joints_runs_them_and_time_picks_the_fastest() {
    let dir = temp_dir("design-time");
    let programs = crate::util::repo_root().join("data/programs");
    let (arcs, pen) = (programs.join("arcs_and_offsets.ngc"), programs.join("pen_plot.ngc"));
    let (arcs, pen) = (arcs.to_str().unwrap(), pen.to_str().unwrap());
    let run = biscara(
        &dir,
        &[
            "design",
            "--l1",
            "190:230:3",
            "--l2",
            "270:270:1",
            "--base",
            "150:200:2",
            "--step",
            "10",
            "--programs",
            arcs,
            pen,
            "--fit",
            "--objective",
            "time",
            "--best",
            "fast.json",
            "-o",
            "d.csv",
        ],
    );
    run.success();
    let text = std::fs::read_to_string(dir.join("d.csv")).unwrap();
    assert!(text.lines().next().unwrap().ends_with(",status,time_s"), "{text}");
    let rows = rows(&text);
    // The built-in robot's row: the sum of the two trajectories' last times.
    let last_t = |args: &[&str]| {
        let run = biscara(&dir, args);
        let last = run.success().stdout.lines().last().unwrap().to_owned();
        number(last.split(',').next().unwrap())
    };
    let expected = last_t(&["joints", arcs]) + last_t(&["joints", "--fit", pen]);
    let default = rows.iter().find(|r| r[1] == "210" && r[2] == "270" && r[3] == "200").unwrap();
    assert!((number(&default[12]) - expected).abs() < 5e-4, "{default:?} vs {expected}");
    // --best is the shortest time.
    let fastest = rows
        .iter()
        .filter(|r| !r[12].is_empty())
        .min_by(|a, b| number(&a[12]).total_cmp(&number(&b[12])));
    let fastest = fastest.expect("a design runs the programs");
    let robot: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("fast.json")).unwrap()).unwrap();
    assert_eq!(robot["links"]["l1"].as_f64(), Some(number(&fastest[1])));
    assert_eq!(robot["base"]["b1x"].as_f64(), Some(number(&fastest[3]) / 2.0));
    // Time needs programs; --fit needs programs.
    biscara(&dir, &[SWEEP, &["--objective", "time"]].concat())
        .expect_code(1)
        .stderr_has("--objective time needs --programs");
    biscara(&dir, &[SWEEP, &["--fit"]].concat()).expect_code(2);
    biscara(&dir, &[SWEEP, &["--programs", "missing.ngc"]].concat()).expect_code(1);
}

/// `--objective cycle`: the cycle_s column is `biscara cycle` on each design at its
/// rectangle's centre (the bodies scaled with the links, the motors fixed), and --best the
/// fastest.
#[test]
fn the_adept_cycle_is_timed_per_design_and_picks_the_fastest() {
    let dir = temp_dir("design-cycle");
    let mut robot: serde_json::Value =
        serde_json::from_str(&biscara(&dir, &["robot"]).success().stdout).unwrap();
    robot["motors"] = serde_json::json!({
        "theta1": {"peak": 0.8, "rated": 0.3}, "theta2": {"peak": 0.8, "rated": 0.3},
        "theta3": {"peak": 0.05, "rated": 0.02}, "d4": {"peak": 40.0, "rated": 20.0}
    });
    // The bodies from the geometry: they scale with each design's links.
    robot.as_object_mut().unwrap().remove("dynamics");
    std::fs::write(dir.join("motors.json"), robot.to_string()).unwrap();
    let args = [
        "--robot",
        "motors.json",
        "design",
        "--l1",
        "190:230:3",
        "--l2",
        "270:270:1",
        "--base",
        "200:200:1",
        "--step",
        "10",
        "--objective",
        "cycle",
        "--best",
        "fast.json",
        "-o",
        "d.csv",
    ];
    biscara(&dir, &args).success();
    let text = std::fs::read_to_string(dir.join("d.csv")).unwrap();
    assert!(text.lines().next().unwrap().ends_with(",status,cycle_s"), "{text}");
    let rows = rows(&text);
    for row in &rows {
        std::fs::write(dir.join("design.json"), {
            let mut design = robot.clone();
            design["links"]["l1"] = serde_json::json!(number(&row[1]));
            design.to_string()
        })
        .unwrap();
        let centre =
            [number(&row[7]) + number(&row[5]) / 2.0, number(&row[8]) + number(&row[6]) / 2.0];
        let at = format!("{},{}", centre[0], centre[1]);
        let run = biscara(&dir, &["--robot", "design.json", "cycle", "--json", "--at", &at]);
        let report: serde_json::Value = serde_json::from_str(&run.success().stdout).unwrap();
        let expected = report["cycle_s"].as_f64().unwrap();
        assert!((number(&row[12]) - expected).abs() < 5e-4, "{row:?} vs {expected}");
    }
    let fastest = rows.iter().min_by(|a, b| number(&a[12]).total_cmp(&number(&b[12]))).unwrap();
    let best: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("fast.json")).unwrap()).unwrap();
    assert_eq!(best["links"]["l1"].as_f64(), Some(number(&fastest[1])));
}

fn rows_of(path: &std::path::Path) -> Vec<Vec<String>> {
    rows(&std::fs::read_to_string(path).unwrap())
}

#[test]
fn bad_design_arguments_are_refused_clearly() {
    let dir = temp_dir("design-bad");
    let base = ["design", "--l2", "230:310:3", "--base", "120:280:3", "-o", "d.csv"];
    for (l1, says) in [
        ("170:250", "'--l1 <MIN:MAX:N>': '170:250' does not have three parts"),
        ("250:170:3", "has MIN above MAX"),
        ("0:100:3", "MIN that is not a positive length"),
        ("170:250:0", "N outside 1..10000"),
        ("170:x:3", "MAX that is no number"),
    ] {
        biscara(&dir, &[&base[..], &["--l1", l1]].concat()).expect_code(2).stderr_has(says);
    }
    let sweep = [&base[..], &["--l1", "170:250:3"]].concat();
    for (flag, value, says) in [
        ("--shard", "5/4", "'--shard <K/N>': '5/4' is not a part of the sweep"),
        ("--shard", "2", "has no '/'"),
        ("--task", "1,2,3", "'--task <X0,Y0,X1,Y1>': '1,2,3' does not have four values"),
        ("--task", "5,0,1,1", "has X0 > X1"),
        ("--objective", "speed", "invalid value 'speed'"),
    ] {
        biscara(&dir, &[&sweep[..], &[flag, value]].concat()).expect_code(2).stderr_has(says);
    }
    biscara(&dir, &["design", "--l1", "170:250:3"]).expect_code(2).stderr_has("--l2");
    biscara(&dir, &[&sweep[..], &["--step", "0"]].concat()).expect_code(1).stderr_has("step");
    // Too many designs, a best nobody reaches (a task outside every workspace).
    biscara(&dir, &["design", "--l1", "1:2:10000", "--l2", "1:2:10000", "--base", "1:2:100"])
        .expect_code(1)
        .stderr_has("more than");
    biscara(&dir, &[&sweep[..], &["--task", "2000,0,2100,100", "--best", "b.json"]].concat())
        .expect_code(1)
        .stderr_has("no design has a rectangle and covers the task");
    assert!(!dir.join("b.json").exists());
    std::fs::remove_file(dir.join("d.csv")).ok();
    // Bad CSVs for merge and atlas: FILE:LINE, exit 1, no output.
    std::fs::write(dir.join("bad.csv"), "index,l1\n1,2\n").unwrap();
    biscara(&dir, &["design", "merge", "bad.csv", "-o", "m.csv"])
        .expect_code(1)
        .stderr_has("bad.csv:1: not a design CSV");
    let header =
        "index,l1,l2,base,area_mm2,rect_w_mm,rect_h_mm,rect_x0_mm,rect_y0_mm,gci,lci_min,status";
    std::fs::write(dir.join("nan.csv"), format!("{header}\n0,1,2,3,inf,0,0,0,0,0,0,ok\n")).unwrap();
    biscara(&dir, &["design", "atlas", "nan.csv", "-o", "a.svg"])
        .expect_code(1)
        .stderr_has("nan.csv:2: area_mm2 'inf' is not finite");
    std::fs::write(dir.join("empty.csv"), format!("{header}\n")).unwrap();
    biscara(&dir, &["design", "atlas", "empty.csv", "-o", "a.svg"])
        .expect_code(1)
        .stderr_has("no designs to draw");
    biscara(&dir, &["design", "merge", "missing.csv", "-o", "m.csv"]).expect_code(1);
    for leftover in ["m.csv", "a.svg", "d.csv"] {
        assert!(!dir.join(leftover).exists(), "{leftover} written");
    }
}

#[test]
fn design_help_is_pinned() {
    let dir = temp_dir("design-help");
    for command in
        [&["design", "--help"][..], &["design", "merge", "--help"], &["design", "atlas", "--help"]]
    {
        let run = biscara(&dir, command);
        run.success();
        assert!(run.stdout.contains("Example:"), "{run}");
        check_golden(&format!("help/{}.txt", command[..command.len() - 1].join("-")), &run.stdout);
    }
}
