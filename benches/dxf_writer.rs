//! Speed of the DXF writer: a mechanism-sized drawing (about 60 entities, 4 dimensions), the
//! same with 360 position layers (one circle each), and the four-bar run's animation drawing
//! (the Chebyshev template, every position on its own layer: about 8 MB of R12), each with
//! the hand-written R12 path ([`to_bytes`]) and the crate path it is checked against
//! ([`to_bytes_via_crate`]).

use std::path::PathBuf;

use criterion::{Criterion, criterion_group, criterion_main};
use mechdraw::draw::dxf::{DxfOptions, to_bytes, to_bytes_via_crate};
use mechdraw::draw::{Aci, DimStyle, Drawing, LineType, LinearMarks, Shape};
use mechdraw::geom::{Point, polar};

fn drawing(position_layers: usize) -> Drawing {
    let mut d = Drawing::new(DimStyle { text_height: 2.5, arrow_size: 2.5 });
    let links = d.layer("LINKS", Aci::BLUE, LineType::Continuous);
    let constr = d.layer("CONSTRUCTION", Aci::RED, LineType::Dashed);
    let dims = d.layer("DIMENSIONS", Aci::GREEN, LineType::Continuous);
    let o = Point::new(0.0, 0.0);
    for i in 0..12 {
        let a = i as f64 * 0.5;
        let p = polar(o, 40.0, a);
        d.add(links, Shape::Polyline { points: vec![o, p, polar(p, 20.0, a + 1.0)], closed: false, width: 0.5 });
        d.add(links, Shape::Circle { center: p, radius: 1.5 });
        d.add(constr, Shape::Arc { center: o, radius: 40.0, start: a, end: a + 0.4 });
        d.add(links, Shape::Arrow { from: p, to: polar(p, 10.0, a + 1.5), head: 2.0 });
        d.text(links, polar(p, 3.0, a), 2.5, format!("A{i} φ{i}"));
    }
    for i in 0..2 {
        let v = Point::new(10.0 * i as f64, 0.0);
        let text = "φ = 40.00°".to_string();
        d.add(
            dims,
            Shape::AngularDimension {
                vertex: v,
                first: polar(v, 5.0, 0.0),
                second: polar(v, 5.0, 0.7),
                radius: 12.0,
                text,
                runs: Default::default(),
            },
        );
        let (p1, p2) = (v, polar(v, 30.0, 0.3));
        d.add(
            dims,
            Shape::LinearDimension {
                p1,
                p2,
                line_at: polar(v, 8.0, 1.9),
                angle: 0.3,
                text: "30".into(),
                marks: LinearMarks::default(),
            },
        );
    }
    for i in 0..position_layers {
        let l = d.layer(&format!("POS_{i:03}"), Aci((i % 255 + 1) as u8), LineType::Continuous);
        d.add(l, Shape::Circle { center: polar(o, 40.0, (i as f64).to_radians()), radius: 0.5 });
    }
    d
}

/// The DXF drawing a run writes for a template (a motion: every position on its own
/// layer), built through the products seam as `mechdraw run` builds it.
fn template_drawing(template: &str) -> Drawing {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("templates/{template}.toml"));
    let loaded = mechdraw::scene::load(&path, &[]).expect("template loads");
    mechdraw::run::products(&loaded, &Default::default()).expect("solves").picture.drawing()
}

fn bench(c: &mut Criterion) {
    let small = drawing(0);
    let many = drawing(360);
    let fourbar = template_drawing("fourbar-chebyshev");
    let opts = DxfOptions::default();
    c.bench_function("dxf_r12_mechanism", |b| b.iter(|| to_bytes(&small, &opts).unwrap()));
    c.bench_function("dxf_r12_360_layers", |b| b.iter(|| to_bytes(&many, &opts).unwrap()));
    c.bench_function("dxf_r12_fourbar_animation", |b| b.iter(|| to_bytes(&fourbar, &opts).unwrap()));
    c.bench_function("dxf_r12_fourbar_animation_via_crate", |b| {
        b.iter(|| to_bytes_via_crate(&fourbar, &opts).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
