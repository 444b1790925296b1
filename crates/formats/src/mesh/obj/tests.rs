use super::*;

#[test]
fn a_quad_becomes_two_triangles_with_its_material() {
    let text = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl asphalt\nf 1 2 3 4\n";
    let m = read_obj("q.obj", text.as_bytes(), None).unwrap();
    assert_eq!(m.triangles.len(), 2);
    assert_eq!(m.material_name(0), Some("asphalt"));
    assert_eq!(m.material_name(1), Some("asphalt"));
    assert_eq!(m.triangle_location(1).line, Some(6));
    // Fan from the first vertex, winding kept: (1,2,3) and (1,3,4).
    let p = |i: u32| m.positions[i as usize];
    let t1 = m.triangles[1].vertices.map(p);
    assert_eq!(t1, [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]);
}

#[test]
fn a_face_is_located_at_the_line_and_column_of_its_f() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n\t  f 2 4 3 1\n";
    let m = read_obj("c.obj", text.as_bytes(), None).unwrap();
    assert_eq!(m.triangle_location(0).to_string(), "c.obj:5:1");
    // A tab and two spaces before the `f`: its third character.
    assert_eq!(m.triangle_location(1).to_string(), "c.obj:6:4");
    assert_eq!(m.triangle_location(2).to_string(), "c.obj:6:4");
}

#[test]
fn every_triangle_of_a_run_of_faces_keeps_its_own_line() {
    // Triangles one per line are stored as one run; a comment, an indented face, a quad
    // and a `usemtl` line each break it, and every triangle still names its face.
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n\
                    f 1 2 3\nf 2 4 3\nf 1 2 4\n# note\nf 1 3 4\n  f 1 2 3\nf 2 4 3\n\
                    f 1 2 4 3\nf 1 2 3\nusemtl m\nf 2 4 3\nf 1 2 4\n";
    let m = read_obj("r.obj", text.as_bytes(), None).unwrap();
    let at: Vec<String> = (0..m.triangles.len())
        .map(|i| m.triangle_location(i).to_string())
        .collect();
    let line = |l: usize, c: usize| format!("r.obj:{l}:{c}");
    assert_eq!(
        at,
        [
            line(5, 1),
            line(6, 1),
            line(7, 1),
            line(9, 1),
            line(10, 3),
            line(11, 1),
            line(12, 1),
            line(12, 1),
            line(13, 1),
            line(15, 1),
            line(16, 1),
        ]
    );
    // Seven runs for ten faces: lines 5-7, 9, 10, 11, 12 (the quad), 13 and 15-16.
    assert_eq!(m.origins.len(), 7);
}

#[test]
fn materials_without_an_mtl_keep_their_names_and_groups_their_order() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nusemtl b\nf 1 2 4\nusemtl a\nf 1 3 4\nusemtl b\nf 2 3 4\n";
    let m = read_obj("m.obj", text.as_bytes(), None).unwrap();
    let names: Vec<_> = (0..4).map(|i| m.material_name(i)).collect();
    assert_eq!(names, [None, Some("b"), Some("a"), Some("b")]);
    assert_eq!(m.materials[0].first_use.line, Some(6));
    assert_eq!(m.triangle_location(3).line, Some(11));
}

#[test]
fn bad_numbers_name_line_and_column() {
    let e = read_obj("b.obj", b"v 0 0 0\nv 1 zero 0\n", None).unwrap_err();
    assert_eq!((e.line, e.column), (2, 5), "{e}");
    let e = read_obj("b.obj", b"v 0 0 0\nv 1 0 NaN\n", None).unwrap_err();
    assert_eq!((e.line, e.column), (2, 7), "{e}");
    assert!(e.message.contains("finite"));
    let e = read_obj("b.obj", b"v 0 0 0\nv 1 0 inf\n", None).unwrap_err();
    assert!(e.message.contains("finite"));
    let e = read_obj("b.obj", b"v 0 0\n", None).unwrap_err();
    assert!(e.message.contains("z coordinate"), "{e}");
}

#[test]
fn short_normal_and_texture_lines_name_line_and_column() {
    // The column is just past the line's last character.
    let e = read_obj("b.obj", b"v 0 0 0\nvn 0 1\n", None).unwrap_err();
    assert_eq!((e.line, e.column), (2, 7), "{e}");
    assert!(e.message.contains("3 numbers after `vn`"), "{e}");
    assert!(e.message.contains("found 2"), "{e}");
    let e = read_obj("b.obj", b"vt 0.5\n", None).unwrap_err();
    assert_eq!((e.line, e.column), (1, 7), "{e}");
    assert!(e.message.contains("2 numbers after `vt`"), "{e}");
    let e = read_obj("b.obj", b"vn 0 x 1\n", None).unwrap_err();
    assert_eq!((e.line, e.column), (1, 6), "{e}");
    // A third texture coordinate (w) is optional.
    let tri = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0 0\nvt 1 0\nvn 0 0 1\nf 1/1/1 2/2/1 3/1/1\n";
    assert!(read_obj("b.obj", tri, None).is_ok());
}

#[test]
fn faces_pointing_past_the_vertices_are_errors() {
    let e = read_obj("b.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", None).unwrap_err();
    assert_eq!((e.line, e.column), (4, 7), "{e}");
    let e = read_obj("b.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", None).unwrap_err();
    assert_eq!(e.line, 4);
    // Negative indices count back from the last vertex.
    let m = read_obj("b.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n", None).unwrap();
    assert_eq!(m.triangles.len(), 1);
}

#[test]
fn texture_and_normal_indices_that_reach_before_the_first_are_errors() {
    let head = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
    for (face, column) in [
        ("f 1/-2 2/1 3/1", 3),
        ("f 1/1 2/0 3/1", 7),
        ("f 1//1 2//1 3//-2", 13),
        ("f 1/1/0 2/1/1 3/1/1", 3),
        ("f 1/x 2/1 3/1", 3),
    ] {
        let text = format!("{head}{face}\n");
        let e = read_obj("t.obj", text.as_bytes(), None).unwrap_err();
        assert_eq!((e.line, e.column), (6, column), "{face}: {e}");
    }
    // In range, from either end, they are fine.
    let text = format!("{head}f 1/1/1 2/-1/-1 3//1\n");
    assert_eq!(
        read_obj("t.obj", text.as_bytes(), None)
            .unwrap()
            .triangles
            .len(),
        1
    );
}

#[test]
fn an_empty_mesh_is_an_error() {
    let e = read_obj("e.obj", b"# nothing\nv 0 0 0\n", None).unwrap_err();
    assert!(e.message.contains("empty mesh"), "{e}");
    assert!(read_obj("e.obj", b"", None).is_err());
}

/// A grid of `n` by `n` quads in the z = 0 plane: `(n + 1)^2` vertex lines first, then
/// one face line per quad, with `usemtl` lines wherever `material_at(face)` says.
fn grid(n: usize, material_at: impl Fn(usize) -> Option<&'static str>) -> String {
    let mut text = String::new();
    for y in 0..=n {
        for x in 0..=n {
            text.push_str(&format!("v {x}.5 {y}.25 0\n"));
        }
    }
    let v = |x: usize, y: usize| y * (n + 1) + x + 1;
    for q in 0..n * n {
        if let Some(name) = material_at(q) {
            text.push_str(&format!("usemtl {name}\n"));
        }
        let (x, y) = (q % n, q / n);
        let (a, b, c, d) = (v(x, y), v(x + 1, y), v(x + 1, y + 1), v(x, y + 1));
        text.push_str(&format!("f {a} {b} {c} {d}\n"));
    }
    text
}

/// Runs `read_obj` on a rayon pool of `threads` threads: with one, the scan and tobj run
/// one after the other; with two, at the same time.
fn read_with_threads(threads: usize, text: &str) -> Result<Mesh, ParseError> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| read_obj("g.obj", text.as_bytes(), None))
}

#[test]
fn errors_late_in_a_big_file_keep_their_line_and_column_at_any_thread_count() {
    // 201 x 201 vertex lines: tobj is still parsing when the scan reaches the bad line.
    let good = grid(200, |_| None);
    let vertex_lines = 201 * 201;
    // A bad number on the last vertex line, third coordinate.
    let mut lines: Vec<&str> = good.lines().collect();
    let last_vertex = lines[vertex_lines - 1].replace(" 0", " 0x1");
    lines[vertex_lines - 1] = &last_vertex;
    let bad_number = lines.join("\n");
    // The last face points one past the last vertex.
    let mut lines: Vec<&str> = good.lines().collect();
    let last = lines.len() - 1;
    let past = format!("f 1 2 {}", vertex_lines + 1);
    lines[last] = &past;
    let bad_face = lines.join("\n");
    for threads in [1, 2] {
        let e = read_with_threads(threads, &bad_number).unwrap_err();
        // "v 200.5 200.25 0x1": the third coordinate starts at column 16.
        assert_eq!((e.line, e.column), (vertex_lines, 16), "{e}");
        assert!(e.message.contains("z coordinate"), "{e}");
        let e = read_with_threads(threads, &bad_face).unwrap_err();
        assert_eq!((e.line, e.column), (last + 1, 7), "{e}");
        assert!(e.message.contains("does not exist"), "{e}");
    }
}

#[test]
#[allow(clippy::float_cmp)] // x + 0.5 and y + 0.25 are exact in binary, and so is their parse
fn materials_follow_usemtl_across_objects_and_groups_at_any_thread_count() {
    // 4 x 4 quads, two triangles each. Quad 0 has no material; `usemtl` lines before
    // quads 1 (a), 5 (b), 6 (b again: no change), 9 (a again) and 12 (c); `o` and `g`
    // lines make tobj split the faces into models.
    let material_at = |q: usize| match q {
        1 | 9 => Some("a"),
        5 | 6 => Some("b"),
        12 => Some("c"),
        _ => None,
    };
    let text = grid(4, material_at)
        .replace("usemtl b\n", "o part\nusemtl b\n")
        .replace("usemtl c\n", "g rest\nusemtl c\n");
    let expected = |q: usize| match q {
        0 => None,
        1..=4 | 9..=11 => Some("a"),
        5..=8 => Some("b"),
        _ => Some("c"),
    };
    for threads in [1, 2] {
        let m = read_with_threads(threads, &text).unwrap();
        assert_eq!(m.triangles.len(), 32);
        let names: Vec<_> = m.materials.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["a", "b", "c"]);
        for t in 0..32 {
            assert_eq!(m.material_name(t), expected(t / 2), "triangle {t}");
        }
        // The grid's quad q has corners at x + 0.5 and y + 0.25 for its (x, y); its
        // first triangle starts at its (x, y) corner, whatever model tobj put it in.
        for q in 0..16 {
            let first = m.triangles[2 * q].vertices[0] as usize;
            let [x, y, _] = m.positions[first];
            assert_eq!(
                [x, y],
                [(q % 4) as f64 + 0.5, (q / 4) as f64 + 0.25],
                "quad {q}"
            );
        }
    }
}

#[test]
fn usemtl_names_are_found_as_the_scan_finds_them() {
    let text = "usemtl a\n  usemtl  b c \r\n# usemtl x\ng usemtl y\nusemtlz w\n\tusemtl a\nusemtl\nusemtl d";
    assert_eq!(usemtl_names(text), ["a", "b c", "d"]);
    // The scan's first uses agree (it rejects the bare `usemtl` line, so without it).
    let scanned =
        text.replace("usemtl\nusemtl d", "usemtl d") + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    let m = read_obj("u.obj", scanned.as_bytes(), None).unwrap();
    let names: Vec<_> = m.materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, usemtl_names(&scanned));
    // A line full of `usemtl` is searched once, not once per occurrence.
    let long = "usemtl".repeat(200_000);
    assert!(usemtl_names(&long).is_empty());
}

#[test]
fn tobj_reads_only_what_the_scan_has_accepted_and_stops_when_it_fails() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    let checked = Checked::default();
    checked.publish(8);
    let mut reader = CheckedText::new(b"# first\n", text, &checked);
    let mut line = String::new();
    reader.read_line(&mut line).unwrap();
    reader.read_line(&mut line).unwrap();
    assert_eq!(line, "# first\nv 0 0 0\n");
    // The next line waits until the scan, on another thread, accepts it.
    std::thread::scope(|s| {
        s.spawn(|| {
            std::thread::sleep(std::time::Duration::from_millis(20));
            checked.publish(16);
        });
        let mut next = String::new();
        reader.read_line(&mut next).unwrap();
        assert_eq!(next, "v 1 0 0\n");
    });
    // Consuming more than was handed out cannot run ahead of the scan.
    reader.consume(100);
    assert_eq!(reader.at, 16);
    checked.set(CheckedState::Failed);
    assert!(reader.read_line(&mut line).is_err());
    assert!(reader.read(&mut [0; 4]).is_err());
    // Once all is accepted, the end of the text is the end of the input.
    checked.publish(text.len());
    let mut rest = String::new();
    reader.read_to_string(&mut rest).unwrap();
    assert_eq!(rest, "v 0 1 0\n");
    assert!(reader.fill_buf().unwrap().is_empty());
}

#[test]
fn mtl_lines_tobj_would_refuse_without_a_place_are_located() {
    let head = "newmtl a\nKd 0.5 0.5 0.5\n";
    for (line, column, fragment) in [
        ("Ka 0.1 x 0.3", 8, "found `x`"),
        ("  Ks 1 1", 3, "three numbers"),
        ("Ke 0 NaN 0", 6, "finite"),
        ("Ns 1e999", 4, "finite"),
        ("d", 1, "a number"),
        ("Ni 1,5", 4, "`1,5`"),
        ("illum 2.5", 7, "0 to 255"),
        ("illum 300", 7, "0 to 255"),
        ("newmtl   ", 1, "material name"),
        ("map_Kd", 1, "texture file name"),
    ] {
        let text = format!("{head}{line}\n");
        let e = check_mtl_lines("t.mtl", &text).unwrap_err();
        assert_eq!((e.line, e.column), (3, column), "{line}: {e}");
        assert!(e.message.contains(fragment), "{line}: {e}");
    }
    let fine =
        "# c\nnewmtl a b\nKa 0 0 0\nKd 1 1 1 # rgb\nNs 10\nd 1\nillum 2\nmap_Kd t.png\nTr 0\n";
    assert!(check_mtl_lines("t.mtl", fine).is_ok());
}

#[test]
fn network_mtllib_is_refused() {
    let e = read_obj(
        "n.obj",
        b"mtllib http://example.com/a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        None,
    )
    .unwrap_err();
    assert_eq!(e.line, 1);
    assert!(e.message.contains("mtllib"), "{e}");
}
