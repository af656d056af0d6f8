use super::*;
use proptest::prelude::*;

const THESIS_EXAMPLE: &str = "# Celo vlevo\n!\nma=0.423;0.727\nmb=0.439;0.640\nn=3\nrelWidth=1.0\nmaxAngle=1.5\nomegaLow=0.6\n\n# Celo vpravo\n!\nma=0.556;0.727\nmb=0.537;0.638\nn=3\nrelWidth=1.0\nmaxAngle=1.5\nomegaLow=0.6\n";

fn p() -> &'static Path {
    Path::new("test.wrk")
}

fn errors_of(text: &str) -> Vec<Diagnostic> {
    parse(text, p()).expect_err("the text has errors").0
}

/// (line, column, kind) of each error, for compact assertions.
fn positions(text: &str) -> Vec<(usize, usize, DiagnosticKind)> {
    errors_of(text)
        .into_iter()
        .map(|d| (d.line, d.column, d.kind))
        .collect()
}

#[test]
fn parses_the_thesis_example() {
    let f = parse(THESIS_EXAMPLE, p()).unwrap();
    assert_eq!(f.groups.len(), 2);
    let a = &f.groups[0];
    assert_eq!(a.comments, vec![" Celo vlevo".to_string()]);
    assert_eq!(a.fibre.ma(), [0.423, 0.727]);
    assert_eq!(a.fibre.mb(), [0.439, 0.640]);
    assert_eq!(a.fibre.n(), 3);
    assert_eq!(a.fibre.rel_width(), 1.0);
    assert_eq!(a.fibre.max_angle(), 1.5);
    assert_eq!(a.fibre.omega_low(), 0.6);
    assert_eq!(f.groups[1].fibre.mb(), [0.537, 0.638]);
}

#[test]
fn keys_case_insensitive_spaces_crlf_comments_and_defaults() {
    let text = "  # header\r\n\r\n ! # group\r\n  MA = 0.1 ; 0.2 \r\nMb=0.3;0.4\t# end\r\nN= 4\r\nRelWidth =0.25\r\nPROFILE = Gauss\r\n";
    let f = parse(text, p()).unwrap();
    assert_eq!(f.groups.len(), 1);
    let fib = &f.groups[0].fibre;
    assert_eq!(fib.ma(), [0.1, 0.2]);
    assert_eq!(fib.mb(), [0.3, 0.4]);
    assert_eq!(fib.n(), 4);
    assert_eq!(fib.rel_width(), 0.25);
    assert_eq!(fib.max_angle(), DEFAULT_MAX_ANGLE);
    assert_eq!(fib.omega_low(), DEFAULT_OMEGA_LOW);
    assert_eq!(fib.profile(), Profile::Gauss);
    assert_eq!(f.groups[0].comments, vec![" header".to_string()]);
}

#[test]
fn a_group_laid_on_the_surface_reads_and_writes_back() {
    let text = "!\nma=0.1;0.2\nmb=0.3;0.2\nn=1\nSpace = Surface\n!\nma=0.1;0.2\nmb=0.3;0.2\nn=1\n";
    let f = parse(text, p()).unwrap();
    assert_eq!(f.groups[0].fibre.space(), Space::Surface);
    assert_eq!(f.groups[1].fibre.space(), Space::Uv, "the default");
    let written = write(&f);
    assert_eq!(written.matches("space=surface").count(), 1, "{written}");
    assert_eq!(parse(&written, p()).unwrap(), f);
    let e = errors_of("!\nma=0.1;0.2\nmb=0.3;0.2\nn=1\nspace=mesh\n");
    assert_eq!((e[0].line, e[0].kind), (5, DiagnosticKind::MalformedValue));
    assert!(e[0].expected.contains("uv, surface"), "{}", e[0].expected);
}

#[test]
fn key_before_first_group() {
    assert_eq!(
        positions("ma=0.1;0.2\n!\nma=0.1;0.2\nmb=0.2;0.2\nn=2\n"),
        vec![(1, 1, DiagnosticKind::KeyBeforeGroup)]
    );
}

#[test]
fn repeated_key_points_at_the_second() {
    assert_eq!(
        positions("!\nma=0.1;0.2\nmb=0.2;0.2\n  MA=0.3;0.3\nn=2\n"),
        vec![(4, 3, DiagnosticKind::RepeatedKey)]
    );
}

#[test]
fn unknown_key_lists_the_known_ones() {
    let e = errors_of("!\nma=0.1;0.2\nmb=0.2;0.2\nn=2\nwidth=3\n");
    assert_eq!(
        (e[0].line, e[0].column, e[0].kind),
        (5, 1, DiagnosticKind::UnknownKey)
    );
    assert!(e[0].expected.contains("relWidth"), "{}", e[0].expected);
    assert_eq!(e[0].found, "width");
}

#[test]
fn malformed_numbers_point_at_the_value() {
    let e = errors_of("!\nma=0.1;zero\nmb = 0.2;0.2\nn=2.5\nrelWidth= abc\n");
    let got: Vec<_> = e
        .iter()
        .map(|d| (d.line, d.column, d.kind, d.found.as_str()))
        .collect();
    assert_eq!(
        got,
        vec![
            (2, 4, DiagnosticKind::MalformedValue, "0.1;zero"),
            (4, 3, DiagnosticKind::MalformedValue, "2.5"),
            (5, 11, DiagnosticKind::MalformedValue, "abc"),
        ]
    );
    assert!(
        errors_of("!\nma=0.1;inf\nmb=0.2;0.2\nn=2\n")[0].kind == DiagnosticKind::MalformedValue
    );
}

#[test]
fn values_out_of_range() {
    let e = errors_of("!\nma=0.1;0.2\nmb=0.2;0.2\nn=0\nmaxAngle=0.25\nomegaLow=2\nrelWidth=0\n");
    let got: Vec<_> = e.iter().map(|d| (d.line, d.column, d.kind)).collect();
    assert_eq!(
        got,
        vec![
            (4, 3, DiagnosticKind::OutOfRange),
            (5, 10, DiagnosticKind::OutOfRange),
            (6, 10, DiagnosticKind::OutOfRange),
            (7, 10, DiagnosticKind::OutOfRange),
        ]
    );
    assert_eq!(e[1].expected, "a number in [1, 2]");
    assert_eq!(e[1].found, "0.25");
}

#[test]
fn missing_required_keys_point_at_the_group() {
    let e = errors_of("!\nma=0.1;0.2\n\n  !\nn=3\n");
    let got: Vec<_> = e.iter().map(|d| (d.line, d.column, d.kind)).collect();
    assert_eq!(
        got,
        vec![
            (1, 1, DiagnosticKind::MissingKey),
            (4, 3, DiagnosticKind::MissingKey)
        ]
    );
    assert!(e[0].expected.contains("`mb`, `n`"), "{}", e[0].expected);
    assert!(e[1].expected.contains("`ma`, `mb`"), "{}", e[1].expected);
}

#[test]
fn identical_ends() {
    assert_eq!(
        positions("!\nma=0.5;0.5\nmb= 0.5 ; 0.5\nn=3\n"),
        vec![(3, 5, DiagnosticKind::IdenticalEnds)]
    );
}

#[test]
fn a_huge_token_is_cut_in_the_message() {
    let text = format!("!\nma={}\n", "9".repeat(10_000_000));
    let e = parse(&text, Path::new("big.wrk")).unwrap_err().to_string();
    assert!(e.len() < 1000, "{} bytes of message", e.len());
    assert!(e.contains("big.wrk:2"), "{}", &e[..e.len().min(300)]);
}

#[test]
fn syntax_error_and_not_utf8() {
    assert_eq!(
        positions("!\nma 0.1\n"),
        vec![
            (1, 1, DiagnosticKind::MissingKey),
            (2, 1, DiagnosticKind::Syntax)
        ]
    );
    let e = parse_bytes(b"!\nma=0.1;0.2\nmb=\xff\n", p()).unwrap_err().0;
    assert_eq!(
        (e[0].line, e[0].column, e[0].kind),
        (3, 4, DiagnosticKind::NotUtf8)
    );
}

#[test]
fn all_errors_are_reported_and_nothing_loads() {
    let text =
        "n=3\n!\nma=0.1;0.2\nmb=0.2;0.2\nn=3\n!\nma=x\nmb=0.2;0.2\nn=3\n!\nmb=0.2;0.2\nbogus=1\n";
    let e = errors_of(text);
    let got: Vec<_> = e.iter().map(|d| (d.line, d.kind)).collect();
    assert_eq!(
        got,
        vec![
            (1, DiagnosticKind::KeyBeforeGroup),
            (7, DiagnosticKind::MalformedValue),
            (10, DiagnosticKind::MissingKey),
            (12, DiagnosticKind::UnknownKey),
        ]
    );
}

#[test]
fn diagnostics_print_as_file_line_column() {
    let e = parse(
        "!\nn=0\nma=0.1;0.2\nmb=0.3;0.2\n",
        Path::new("assets/x.wrk"),
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "assets/x.wrk:2:3: value out of range: expected an integer in 1..=1000, found `0`"
    );
}

#[test]
fn writer_keeps_comments_and_reads_back() {
    let f = parse(THESIS_EXAMPLE, p()).unwrap();
    let text = write(&f);
    assert!(
        text.starts_with("# Celo vlevo\n!\nma=0.423;0.727\n"),
        "{text}"
    );
    assert_eq!(parse(&text, p()).unwrap(), f);
}

fn arb_group() -> impl Strategy<Value = WrinkleGroup> {
    let point = (-1.0f32..2.0, -1.0f32..2.0).prop_map(|(u, v)| [u, v]);
    (
        point.clone(),
        point,
        2u32..50,
        1e-6f32..=1.0,
        1.0f32..=2.0,
        0.0f32..=1.0,
        prop::sample::select(Profile::ALL.to_vec()),
        0.0f32..=100.0,
        prop::collection::vec("[ -~&&[^\n\r]]{0,20}", 0..3),
        prop::sample::select(Space::ALL.to_vec()),
    )
        .prop_filter_map(
            "ma ≠ mb",
            |(ma, mb, n, w, a, o, prof, depth, comments, space)| {
                let fibre = Fibre::new(ma, mb, n)
                    .ok()?
                    .with_rel_width(w)
                    .ok()?
                    .with_max_angle(a)
                    .ok()?
                    .with_omega_low(o)
                    .ok()?
                    .with_depth(depth)
                    .ok()?
                    .with_profile(prof)
                    .with_space(space);
                Some(WrinkleGroup {
                    fibre,
                    age: None,
                    comments,
                })
            },
        )
}

proptest! {
    #[test]
    fn round_trip(groups in prop::collection::vec(arb_group(), 0..6),
                  trailing in prop::collection::vec("[ -~&&[^\n\r]]{0,12}", 0..2)) {
        let file = WrinkleFile { groups, trailing_comments: trailing };
        let text = write(&file);
        let back = parse(&text, p()).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(back, file);
    }
}
