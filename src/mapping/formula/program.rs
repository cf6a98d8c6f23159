//! A formula compiled for the renderer: exmex's evaluation over symbols ([`Sym`]) gives the
//! tree exmex evaluates, in its own order; here it becomes a flat list of instructions over
//! registers, run once per hit without exmex's per-call bookkeeping (about 50 ns a call, more
//! than the lecture's whole spherical map). The functions are [`un`] and [`bin`], exmex's, so a
//! program's value is exmex's, bit for bit (tested on many formulas).

use super::ops::{Bin, Sym, Un, bin, un};
use std::collections::HashMap;
use std::sync::Arc;

/// One instruction: its result goes to the register of its index.
#[derive(Clone, Copy, Debug)]
enum Instr {
    /// The input of this index.
    Input(usize),
    Num(f64),
    Un(Un, u32),
    Bin(Bin, u32, u32),
}

/// A compiled formula: instructions in order, the last one's register the value.
#[derive(Clone, Debug)]
pub struct Program {
    code: Vec<Instr>,
}

/// Registers kept on the stack; longer programs use the heap.
const STACK_REGISTERS: usize = 64;

impl Program {
    /// The program of the tree `sym`, whose variable `i` is input `slots[i]`.
    pub fn compile(sym: &Sym, slots: &[usize]) -> Self {
        let mut p = Self { code: Vec::new() };
        let mut seen = HashMap::new();
        p.emit(sym, slots, &mut seen);
        p
    }

    fn emit(&mut self, sym: &Sym, slots: &[usize], seen: &mut HashMap<*const Sym, u32>) -> u32 {
        let instr = match sym {
            Sym::Num(x) => Instr::Num(*x),
            Sym::Var(i) => Instr::Input(slots.get(*i).copied().unwrap_or(usize::MAX)),
            Sym::Un(op, a) => Instr::Un(*op, self.shared(a, slots, seen)),
            Sym::Bin(op, a, b) => {
                let a = self.shared(a, slots, seen);
                let b = self.shared(b, slots, seen);
                Instr::Bin(*op, a, b)
            }
        };
        self.code.push(instr);
        (self.code.len() - 1) as u32
    }

    /// A subtree, emitted once however often it is shared.
    fn shared(
        &mut self,
        a: &Arc<Sym>,
        slots: &[usize],
        seen: &mut HashMap<*const Sym, u32>,
    ) -> u32 {
        let key = Arc::as_ptr(a);
        if let Some(&r) = seen.get(&key) {
            return r;
        }
        let r = self.emit(a, slots, seen);
        seen.insert(key, r);
        r
    }

    /// The value at `inputs` (NaN for an input not given).
    #[inline]
    #[must_use]
    pub fn eval(&self, inputs: &[f64]) -> f64 {
        if self.code.len() <= STACK_REGISTERS {
            let mut regs = [0.0; STACK_REGISTERS];
            self.run(inputs, &mut regs)
        } else {
            let mut regs = vec![0.0; self.code.len()];
            self.run(inputs, &mut regs)
        }
    }

    #[inline]
    fn run(&self, inputs: &[f64], regs: &mut [f64]) -> f64 {
        let mut last = f64::NAN;
        for (i, instr) in self.code.iter().enumerate() {
            let r = |k: u32| regs.get(k as usize).copied().unwrap_or(f64::NAN);
            last = match *instr {
                Instr::Input(k) => inputs.get(k).copied().unwrap_or(f64::NAN),
                Instr::Num(x) => x,
                Instr::Un(op, a) => un(op, r(a)),
                Instr::Bin(op, a, b) => bin(op, r(a), r(b)),
            };
            if let Some(slot) = regs.get_mut(i) {
                *slot = last;
            }
        }
        last
    }
}
