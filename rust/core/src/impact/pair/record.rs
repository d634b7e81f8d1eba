//! The record of a pair (docs/model.md, section 17.4): every integrator's last word.

use crate::impact::record::{Record, StopReason};
use crate::integrate::Lanes;
use crate::model::{Initial, Pair};

/// The normal at separation: the direction of the centres' line where they last were `reach`
/// apart, found from the final state `q`, `v` by going back along the free flight since
/// (no force acts once apart; a timed-out impact keeps its current direction).
pub(super) fn separation_normal(q: &Lanes, v: &Lanes, reach: f64) -> [f64; 2] {
    let (x, y, gx, gy) = (q[0], q[1], v[0], v[1]);
    let (rg, g2, r2) = (x * gx + y * gy, gx * gx + gy * gy, x * x + y * y);
    let disc = rg * rg - g2 * (r2 - reach * reach);
    let tau = if r2 > reach * reach && g2 > 0.0 && disc >= 0.0 {
        (rg - disc.sqrt()) / g2
    } else {
        0.0
    };
    let (xs, ys) = (x - gx * tau, y - gy * tau);
    let d = xs.hypot(ys);
    [xs / d, ys / d]
}

/// Completes a pair's record (section 17 of docs/model.md): the first-touch normal is +y and
/// its tangent +x, g0 = (init.vx, init.vy); `qv` the final lanes, `y0` the centres' distance
/// at first touch and `ns` the line of centres at separation.
pub(super) fn close_pair(
    rec: &mut Record,
    pair: &Pair,
    init: &Initial,
    (q, v): (&Lanes, &Lanes),
    (y0, ns): (f64, [f64; 2]),
) {
    let (m1, m2, ms) = (pair.particle.mass, pair.m2, pair.m_star);
    let (r1, r2) = (pair.particle.r, pair.r2);
    let g0 = [init.vx, init.vy];
    let speed = g0[0].hypot(g0[1]);
    rec.energy_out = pair.kinetic_energy(v);
    rec.energy_residual =
        (rec.energy_out - rec.energy_in - rec.work_normal - rec.work_friction) / rec.energy_in;
    rec.e_n = -v[1] / g0[1];
    rec.e_n_sep = -(v[0] * ns[0] + v[1] * ns[1]) / g0[1];
    rec.normal_rotation_deg = (-ns[0]).atan2(ns[1]).to_degrees();
    rec.e_t = (g0[0] != 0.0).then(|| v[0] / g0[0]);
    rec.e_kin = v[0].hypot(v[1]) / speed;
    rec.omega_out = v[2];
    rec.partner_omega_out = v[3];
    let v_cp = g0[0] + r1 * init.omega + r2 * init.partner_omega;
    rec.beta = (v_cp != 0.0).then(|| -(v[0] + r1 * v[2] + r2 * v[3]) / v_cp);
    rec.rebound_angle_deg = v[1].atan2(v[0]).to_degrees();
    // Lab velocities in the frame where the partner was at rest: the centre of mass moves
    // at m1 g0 / M throughout.
    let total = m1 + m2;
    let cm = [m1 * g0[0] / total, m1 * g0[1] / total];
    let v1 = [cm[0] + m2 / total * v[0], cm[1] + m2 / total * v[1]];
    let v2 = [cm[0] - m1 / total * v[0], cm[1] - m1 / total * v[1]];
    (rec.vx_out, rec.vy_out) = (v1[0], v1[1]);
    (rec.partner_vx_out, rec.partner_vy_out) = (v2[0], v2[1]);
    let p = [
        m1 * v1[0] + m2 * v2[0] - m1 * g0[0],
        m1 * v1[1] + m2 * v2[1] - m1 * g0[1],
    ];
    rec.momentum_residual = Some(p[0].hypot(p[1]) / (ms * speed));
    let l_in = pair.angular_momentum(
        &[0.0, y0, 0.0, 0.0],
        &[g0[0], g0[1], init.omega, init.partner_omega],
    );
    let l_out = pair.angular_momentum(q, v);
    rec.angular_momentum_residual = Some((l_out - l_in) / (ms * speed * (r1 + r2)));
    rec.timed_out = rec.stop != StopReason::Separated;
    rec.separated = !rec.timed_out;
}
