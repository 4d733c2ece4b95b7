use gas::dsmc::{theory, SpatialDsmc, SpatialOptions};
use restitution::Constant;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let width: f64 = args[1].parse().unwrap();
    let (n, phi, eps) = (20_000, 0.1, 0.9);
    let system = gas::init::monodisperse::<3>(n, phi, 1.0, 1.0, 1.0, 3).unwrap();
    let density = n as f64 / system.volume();
    let options = SpatialOptions {
        cell_width: if width > 0.0 { Some(width) } else { None },
        ..Default::default()
    };
    let mut e = SpatialDsmc::new(
        system,
        phi,
        Box::new(Constant::new(eps).unwrap()),
        4,
        options,
    )
    .unwrap();
    let omega0 = theory::collision_frequency::<3>(density, 1.0, 1.0, 1.0, phi);
    let a2 = theory::van_noije_ernst_a2::<3>(eps);
    let tau = theory::haff_time::<3>(eps, omega0 * (1.0 + 3.0 * a2 / 16.0));
    println!(
        "F {:.3} width {:.3} per cell {:.3}",
        e.weight(),
        e.cell_width(),
        e.particles_per_cell()
    );
    for x in [1.0, 4.0] {
        e.run_until(x * tau);
        let ratio = gas::observe::temperature(e.system()) * (1.0f64 + x).powi(2);
        let c = e.collisions_per_particle()
            / theory::haff_collisions_per_particle(omega0 * (1.0 - a2 / 16.0), tau, x * tau);
        println!("t/tau {x}: T/T_Haff {ratio:.4} coll/theory {c:.4}");
    }
}
