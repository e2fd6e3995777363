//! `biscara clf`, `post` and `gen`: golden files for every example in `data/`, the bad inputs of
//! issue 3, atomic outputs and help texts.

use std::path::{Path, PathBuf};

use crate::golden::check_golden;
use crate::util::{Run, biscara, biscara_with_input, repo_root, temp_dir};

/// The files in `data/FOLDER` ending in `.EXT`, sorted.
pub fn data_files(folder: &str, ext: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo_root().join("data").join(folder))
        .unwrap_or_else(|err| panic!("data/{folder}: {err}"))
        .map(|entry| entry.expect("entry").path())
        .filter(|path| path.extension().is_some_and(|e| e == ext))
        .collect();
    files.sort();
    assert!(!files.is_empty(), "no .{ext} files in data/{folder}");
    files
}

/// The file name without its extension.
pub fn stem(path: &Path) -> String {
    path.file_stem().and_then(|s| s.to_str()).expect("file name").to_owned()
}

fn path_arg(path: &Path) -> &str {
    path.to_str().expect("UTF-8 path")
}

fn read(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|err| panic!("{}: {err}", path.display()))
}

/// Every job in `data/jobs/`: `clf` → CL golden, `gen` → G-code golden (plain and numbered),
/// `post` of the CL = `gen`, `gen --clf` = `clf`.
#[test]
fn jobs_in_data_match_their_golden_files() {
    let dir = temp_dir("golden-jobs");
    for job in data_files("jobs", "txt") {
        let name = stem(&job);
        let clf = biscara(&dir, &["clf", path_arg(&job)]);
        clf.success();
        check_golden(&format!("clf/{name}.cl"), &clf.stdout);

        let generated =
            biscara(&dir, &["gen", path_arg(&job), "--clf", "kept.cl", "-o", "job.ngc"]);
        generated.success();
        assert_eq!(generated.stdout, "", "{generated}");
        let gcode = read(&dir.join("job.ngc"));
        check_golden(&format!("gen/{name}.ngc"), &gcode);
        assert_eq!(read(&dir.join("kept.cl")), clf.stdout, "gen --clf writes what clf writes");

        std::fs::write(dir.join("job.cl"), &clf.stdout).expect("write");
        let post = biscara(&dir, &["post", "job.cl"]);
        assert_eq!(post.success().stdout, gcode, "post of clf's CL = gen");
        assert_eq!(post.stderr, "", "our own CL has no post words to ignore");

        let numbered = biscara(&dir, &["gen", "--line-numbers", path_arg(&job)]);
        check_golden(&format!("gen/{name}.numbered.ngc"), &numbered.success().stdout);
    }
}

/// Every CL file in `data/cl/`: `post` → G-code golden (plain and numbered), the ignored post
/// words listed once on stderr.
#[test]
fn cl_files_in_data_match_their_golden_files() {
    let dir = temp_dir("golden-cl");
    for cl in data_files("cl", "cl") {
        let name = stem(&cl);
        let post = biscara(&dir, &["post", path_arg(&cl), "-o", "out.ngc"]);
        post.success();
        check_golden(&format!("post/{name}.ngc"), &read(&dir.join("out.ngc")));
        check_golden(&format!("post/{name}.stderr"), &post.stderr.replace(path_arg(&cl), "CL"));
        let numbered = biscara(&dir, &["post", "--line-numbers", path_arg(&cl)]);
        check_golden(&format!("post/{name}.numbered.ngc"), &numbered.success().stdout);
    }
}

#[test]
fn the_bundled_job_gives_its_pick_and_place_program() {
    let dir = temp_dir("bundled-job");
    let run = biscara(&dir, &["gen", path_arg(&repo_root().join("data/jobs/pick_place.txt"))]);
    let gcode = &run.success().stdout;
    // The program's first lines and its last.
    assert!(gcode.starts_with(
        "%\n(PICK AND PLACE)\nG21 G17 G90 G94\nG0 X0.000 Y400.000 Z100.000 C0.000\n\
         G0 X150.000 Y320.000 Z60.000 C30.000\nG1 Z10.000 F3000.0\nM3 (pick)\nG4 P0.300\n\
         G1 Z60.000\n"
    ));
    assert!(gcode.contains("\nM4 (place)\n"));
    assert!(gcode.ends_with("\nM2\n%\n"));
}

#[test]
fn standard_input_and_default_settings() {
    let dir = temp_dir("stdin");
    let points = b"PICK 150,320,10,30\nPlace\t-150 300 20 0\n";
    let run = biscara_with_input(&dir, &["clf", "-"], Some(points));
    let cl = &run.success().stdout;
    // Defaults: the robot's home pose, 50 mm approach, 3000 mm/min, no dwell.
    assert!(cl.contains("GOTO/0.0000,460.7987,100.0000,0.0000\n"), "{run}");
    assert!(cl.contains("GOTO/150.0000,320.0000,60.0000,30.0000\nFEDRAT/MMPM,3000.0000\n"));
    assert!(!cl.contains("DELAY"));
    let post = biscara_with_input(&dir, &["post", "-"], Some(cl.as_bytes()));
    let generated = biscara_with_input(&dir, &["gen", "-"], Some(points));
    assert_eq!(post.success().stdout, generated.success().stdout);
}

#[test]
fn the_robot_file_decides_what_is_reachable() {
    let dir = temp_dir("robot-reach");
    std::fs::write(dir.join("short.json"), r#"{"links": {"l1": 150, "l2": 200}}"#).expect("write");
    std::fs::write(
        dir.join("job.txt"),
        "home 0 300 100 0\npick 150 320 10 30\nplace -150 300 20 0\n",
    )
    .expect("write");
    biscara(&dir, &["clf", "job.txt"]).success();
    biscara(&dir, &["--robot", "short.json", "clf", "job.txt"])
        .expect_code(1)
        .stderr_has("job.txt:2: pick (x, y, z, c) = (150, 320, 10, 30) is unreachable: chain");
}

/// Runs `biscara COMMAND FILE -o out.EXT` on `content` and checks: exit 1, the message, no
/// output file, no temporary file left behind.
#[track_caller]
fn check_rejected(command: &str, content: &[u8], message: &str) -> Run {
    let dir = temp_dir("bad-input");
    let (input, output) = match command {
        "post" => ("job.cl", "out.ngc"),
        "clf" => ("points.txt", "out.cl"),
        _ => ("points.txt", "out.ngc"),
    };
    std::fs::write(dir.join(input), content).expect("write");
    let run = biscara(&dir, &[command, input, "-o", output]);
    run.expect_code(1).stderr_has(message);
    assert!(!run.stderr.contains("panicked"), "{run}");
    let left: Vec<_> =
        std::fs::read_dir(&dir).expect("dir").map(|e| e.expect("entry").file_name()).collect();
    assert_eq!(left, vec![std::ffi::OsString::from(input)], "no output file\n{run}");
    run
}

const PAIR: &str = "pick 150 320 10 30\nplace -150 300 20 0\n";

#[test]
fn bad_points_files_get_a_clear_error_and_no_output() {
    let cases: Vec<(String, &str)> = vec![
        (String::new(), "points.txt:1: no pick/place pair"),
        ("home 0 400 100 0\n".into(), "points.txt:1: no pick/place pair"),
        ("place -150 300 20 0\npick 150 320 10 30\n".into(), "points.txt:1: place before pick"),
        (
            format!("{PAIR}pick 120 250 10 -45\n"),
            "points.txt:3: the pick on this line has no place",
        ),
        (
            format!("{PAIR}{PAIR}pick 120 250 10 -45\n"),
            "points.txt:5: the pick on this line has no place",
        ),
        (
            "pick 150 320 10\nplace -150 300 20 0\n".into(),
            "points.txt:1: `pick` takes a pose of 4 values",
        ),
        (
            "pick 150 NaN 10 30\nplace -150 300 20 0\n".into(),
            "points.txt:1: `NaN` is not a finite number",
        ),
        (
            "pick 150 320 inf 30\nplace -150 300 20 0\n".into(),
            "points.txt:1: `inf` is not a finite number",
        ),
        (
            "pick 150 320 10 30\nplace -150 1e999 20 0\n".into(),
            "points.txt:2: `1e999` is not a finite number",
        ),
        ("feed -inf\n".into(), "points.txt:1: `-inf` is not a finite number"),
        (
            "pick 1e300 320 10 30\nplace -150 300 20 0\n".into(),
            "points.txt:1: `pick` 1e300 is out of range: coordinates must lie within ±1e6",
        ),
        (
            "pick 500 320 10 30\nplace -150 300 20 0\n".into(),
            "points.txt:1: pick (x, y, z, c) = (500, 320, 10, 30) is unreachable: chain 1 cannot reach (x, y) = (500.000, 320.000): 32.250 mm too far",
        ),
        (
            "approach 50\npick 150 320 10 30\nplace -150 300 80 0\n".into(),
            "points.txt:3: approach pose above the place (x, y, z, c) = (-150, 300, 130, 0) is unreachable: d4 = -30.000 mm is outside its limits [0, 100] by 30.000 mm",
        ),
        (
            "pick 150 320 10 30\nplace -150 300 20 600\n".into(),
            "points.txt:2: place (x, y, z, c) = (-150, 300, 20, 600) is unreachable: theta3 = 551.221° is outside its limits [-180, 180] by 371.221°",
        ),
        ("pick 150 320 10 30\nplace 0 60 10 0\n".into(), "beyond a type-2 singularity"),
        ("# job\nmove 150 320 10 30\n".into(), "points.txt:2: unknown keyword `move`"),
        (
            "home 0 400 120 0\n".into(),
            "points.txt:1: home (x, y, z, c) = (0, 400, 120, 0) is unreachable",
        ),
        (
            format!("x{}\n", "y".repeat(100_000)),
            "points.txt:1: the line is longer than 65536 bytes",
        ),
    ];
    for (content, message) in &cases {
        for command in ["clf", "gen"] {
            check_rejected(command, content.as_bytes(), message);
        }
    }
    let binary: Vec<u8> = (0..=255u8).cycle().take(2000).collect();
    check_rejected("clf", &binary, "points.txt:1: not a text file");
    check_rejected("gen", b"pick 150 320 10 30\n\xff\xfe\x00\x01", "points.txt:2: not a text file");
    check_rejected("clf", b"\x7fELF\x02\x01\x01\x00\x00\x00", "points.txt:1: not a text file");
}

#[test]
fn bad_cl_files_get_a_clear_error_and_no_output() {
    let head = "PARTNO/T\nUNITS/MM\nRAPID\nGOTO/0,400,100,0\nFEDRAT/MMPM,3000\n";
    let cases: Vec<(String, &str)> = vec![
        (String::new(), "job.cl:1: the CL file is empty"),
        ("$$ only a comment\n".into(), "job.cl:1: the CL file is empty"),
        (
            format!("{head}GOTO/1,2,3,4,5\nFINI\n"),
            "job.cl:6: GOTO takes 3 (x,y,z), 4 (x,y,z,c) or 6 (x,y,z,i,j,k) values, found 5",
        ),
        (
            format!("{head}GOTO/1,2,3,0,1,0\nFINI\n"),
            "job.cl:6: GOTO: tool axis (i, j, k) = (0, 1, 0) is not (0, 0, 1)",
        ),
        (
            format!("{head}CIRCLE/0,400,100,0,0,1,10\nPICK\nFINI\n"),
            "job.cl:6: CIRCLE is not followed by a GOTO (found PICK on line 7)",
        ),
        (
            format!("{head}CIRCLE/0,400,100,0,0,1,10\nFINI\n"),
            "job.cl:6: CIRCLE is not followed by a GOTO (found FINI on line 7)",
        ),
        (
            format!("{head}CIRCLE/0,400,100,0,0,1,10\n"),
            "job.cl:6: CIRCLE is not followed by a GOTO (found the end of the file)",
        ),
        (format!("{head}GOTO/1,NaN,3\nFINI\n"), "job.cl:6: GOTO: `NaN` is not a finite number"),
        (format!("{head}GOTO/1,2,inf\nFINI\n"), "job.cl:6: GOTO: `inf` is not a finite number"),
        (format!("{head}GOTO/1e999,2,3\nFINI\n"), "job.cl:6: GOTO: `1e999` is not a finite number"),
        (format!("{head}GOTO/1e300,2,3\nFINI\n"), "job.cl:6: GOTO: 1e300 is out of range"),
        (
            format!("{head}CYCLE/DRILL,10,IPM,5\nFINI\n"),
            "job.cl:6: unknown CL statement `CYCLE/DRILL,10,IPM,5`",
        ),
        ("PARTNO/T\nFEDRAT/MMPR,0.1\nFINI\n".into(), "job.cl:2: FEDRAT: unexpected `MMPR`"),
        (format!("{head}GOTO/1,2,3\n"), "job.cl:6: the CL file ends without FINI"),
        (format!("{head}GOTO/1,2,$\n"), "job.cl:6: GOTO: a value is missing"),
        (format!("x{}\n", "y".repeat(100_000)), "job.cl:1: the line is longer than 65536 bytes"),
        (format!("GOTO/1,2,${}", "\n12$".repeat(40_000)), "the line is longer than 65536 bytes"),
    ];
    for (content, message) in &cases {
        check_rejected("post", content.as_bytes(), message);
    }
    let binary: Vec<u8> = (0..=255u8).cycle().take(2000).collect();
    check_rejected("post", &binary, "job.cl:1: not a text file");
    check_rejected("post", b"PARTNO/X\n\x00\x01\x02", "job.cl:2: not a text file");
}

#[test]
fn a_failed_run_keeps_the_earlier_good_file() {
    let dir = temp_dir("keep-good");
    std::fs::write(dir.join("good.txt"), PAIR).expect("write");
    std::fs::write(dir.join("bad.txt"), "pick 150 320 10 30\n").expect("write");
    biscara(&dir, &["gen", "good.txt", "-o", "job.ngc", "--clf", "job.cl"]).success();
    let (gcode, cl) = (read(&dir.join("job.ngc")), read(&dir.join("job.cl")));
    biscara(&dir, &["gen", "bad.txt", "-o", "job.ngc", "--clf", "job.cl"])
        .expect_code(1)
        .stderr_has("bad.txt:1: the pick on this line has no place");
    assert_eq!(read(&dir.join("job.ngc")), gcode);
    assert_eq!(read(&dir.join("job.cl")), cl);
    let mut left: Vec<_> =
        std::fs::read_dir(&dir).expect("dir").map(|e| e.expect("e").file_name()).collect();
    left.sort();
    assert_eq!(left.len(), 4, "no temporary files: {left:?}");
}

#[test]
fn usage_errors_exit_with_2() {
    let dir = temp_dir("programming-usage");
    std::fs::write(dir.join("job.txt"), PAIR).expect("write");
    biscara(&dir, &["gen", "job.txt", "--clf", "-"]).expect_code(2).stderr_has("standard output");
    biscara(&dir, &["clf"]).expect_code(2);
    biscara(&dir, &["post", "a.cl", "b.cl"]).expect_code(2);
    biscara(&dir, &["gen", "job.txt", "--bogus"]).expect_code(2);
    biscara(&dir, &["post", "missing.cl"]).expect_code(1).stderr_has("cannot read missing.cl");
    // --clf - is fine when the G-code goes to a file.
    let run = biscara(&dir, &["gen", "job.txt", "--clf", "-", "-o", "job.ngc"]);
    assert!(run.success().stdout.starts_with("PARTNO/PICK AND PLACE\n"));
}

#[test]
fn programming_help_texts_are_pinned() {
    let dir = temp_dir("programming-help");
    for command in ["clf", "post", "gen"] {
        let run = biscara(&dir, &[command, "--help"]);
        run.success();
        assert!(run.stdout.contains("Example:"), "{run}");
        check_golden(&format!("help/{command}.txt"), &run.stdout);
    }
}
