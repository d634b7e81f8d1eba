//! The works of the contact forces along fixed steps: quadratures of their powers, sampled at
//! the end of each step (the plate's loop and the pair's share them).

/// The work of a force along the steps, from its power at the end of each step: each step's
/// share is the integral of the parabola through the last three powers (third order, for
/// unequal steps too), the first step of a smooth stretch (from touch or from an event, where
/// the power may jump) the trapezoid's.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Work {
    pub(crate) total: f64,
    /// Power at the end of the last step and of the one before.
    p: f64,
    p_prev: f64,
    /// Length of the last step; 0 at the start of a stretch.
    h: f64,
    /// One step into the stretch (its first share is still the trapezoid's).
    second: bool,
}

impl Work {
    pub(crate) fn starting_at(p: f64) -> Self {
        Work {
            total: 0.0,
            p,
            p_prev: 0.0,
            h: 0.0,
            second: false,
        }
    }

    /// A new smooth stretch from power `p`, keeping the work so far.
    pub(crate) fn restart(self, p: f64) -> Self {
        Work {
            total: self.total,
            ..Work::starting_at(p)
        }
    }

    /// The trapezoid's share, as for the exact disc (see `integrate_on`).
    #[inline(always)]
    pub(crate) fn push_trapezoid(&mut self, h: f64, p: f64) {
        self.total += 0.5 * h * (self.p + p);
        self.p = p;
    }

    #[inline(always)]
    pub(crate) fn push(&mut self, h: f64, p: f64) {
        let h1 = self.h;
        if self.second && h == h1 {
            // The stretch's first step was a trapezoid: now that a third power is known, its
            // share becomes the parabola's, h (5 p0 + 8 p1 - p2) / 12.
            self.total += h * (2.0 * self.p - self.p_prev - p) * (1.0 / 12.0);
        }
        self.second = h1 == 0.0;
        self.total += if h == h1 {
            h * (5.0 * p + 8.0 * self.p - self.p_prev) * (1.0 / 12.0)
        } else if h1 > 0.0 && h <= 4.0 * h1 {
            // Unequal steps (events, refined steps); far longer than the last one (after a
            // tiny cut) the parabola would amplify round-off, and the trapezoid is used.
            let s = h1 + h;
            h / 6.0
                * (p * (2.0 * h + 3.0 * h1) / s + self.p * (h + 3.0 * h1) / h1
                    - self.p_prev * h * h / (h1 * s))
        } else {
            0.5 * h * (self.p + p)
        };
        (self.p_prev, self.p, self.h) = (self.p, p, h);
    }
}

/// The powers of a contact's forces at one instant: the normal force's elastic part, its
/// damping part and the tangential force's.
pub(crate) type Powers = (f64, f64, f64);

/// The works of the normal force, of its dashpot alone, and of the tangential force along the
/// steps. With `high_order` (Gear-5, whose energy is accurate to far below the trapezoid's
/// error) each is the parabola's quadrature, a new smooth stretch starting where the normal
/// force is clipped to zero or released (its power kinks there: a parabola through both sides
/// would be worse than the trapezoid); otherwise the trapezoid's (Verlet's velocity update is
/// itself a trapezoid of the forces, so the trapezoid closes its balance).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Works {
    pub(crate) normal: Work,
    pub(crate) damping: Work,
    pub(crate) tangential: Work,
    high_order: bool,
    was_pushing: bool,
}

impl Works {
    pub(crate) fn new(high_order: bool) -> Self {
        Works {
            normal: Work::starting_at(0.0),
            damping: Work::starting_at(0.0),
            tangential: Work::starting_at(0.0),
            high_order,
            was_pushing: false,
        }
    }

    /// A new smooth stretch from the powers `p` (at touch or an event, where they may jump),
    /// keeping the works so far.
    pub(crate) fn restart(&mut self, (p_el, p_d, p_t): Powers) {
        self.normal = self.normal.restart(p_el + p_d);
        self.damping = self.damping.restart(p_d);
        self.tangential = self.tangential.restart(p_t);
    }

    /// The bodies are apart (no force, no power): the next contact starts a new stretch.
    pub(crate) fn part(&mut self) {
        self.restart((0.0, 0.0, 0.0));
        self.was_pushing = false;
    }

    /// Adds a step of length `h` that ends with the powers `p`, the normal force `pushing` or
    /// not.
    #[inline(always)]
    pub(crate) fn add(&mut self, h: f64, p: Powers, pushing: bool) {
        let (p_el, p_d, p_t) = p;
        if !self.high_order {
            self.normal.push_trapezoid(h, p_el + p_d);
            self.damping.push_trapezoid(h, p_d);
            self.tangential.push_trapezoid(h, p_t);
        } else if pushing == self.was_pushing {
            self.normal.push(h, p_el + p_d);
            self.damping.push(h, p_d);
            self.tangential.push(h, p_t);
        } else {
            self.normal.push_trapezoid(h, p_el + p_d);
            self.damping.push_trapezoid(h, p_d);
            self.tangential.push_trapezoid(h, p_t);
            self.restart(p);
        }
        self.was_pushing = pushing;
    }
}
