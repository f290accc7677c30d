//! What the command line prints on stderr (issue 28, item 4): warnings one plain line each, no
//! colour codes or timestamps when stderr is not a terminal (here it is a pipe).

mod common;

#[test]
fn warnings_are_plain_lines_without_escape_codes() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x.png");
    // At 128×96 the default preset's labels do not fit: a warning path; `verbose` adds -v.
    let render = |verbose: bool| {
        let args = [
            "render",
            "graphs/default.ron",
            "--size",
            "128x96",
            "-o",
            out.to_str().unwrap(),
        ];
        let args: Vec<&str> = verbose.then_some("-v").into_iter().chain(args).collect();
        let o = common::hatchery(&args);
        assert!(o.status.success());
        let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
        assert!(
            !stderr.contains('\x1b'),
            "escape codes on a pipe: {stderr:?}"
        );
        stderr
    };
    let stderr = render(false);
    assert!(
        stderr
            .lines()
            .any(|l| l.starts_with("warning: layout: no room in the frame")),
        "{stderr}"
    );
    // With -v the detailed format, still without colour on a pipe.
    let stderr = render(true);
    assert!(stderr.contains("INFO"), "{stderr}");
    // An error is one line.
    let o = common::hatchery(&["render", "graphs/nope.ron"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("error: ") && !stderr.contains('\x1b'),
        "{stderr}"
    );
}
