//! A formula compiled for the renderer: exmex's evaluation over symbols ([`Sym`]) records the
//! steps exmex takes, in its own order, on a [`Tape`]; here the steps one value needs become a
//! flat list of instructions over registers, run once per hit without exmex's per-call
//! bookkeeping (about 50 ns a call, more than the lecture's whole spherical map). The functions
//! are [`un`] and [`bin`], exmex's, so a program's value is exmex's, bit for bit (tested on many
//! formulas). Compiling walks the tape in order, never a tree, so no formula's shape costs
//! stack.

use super::ops::{Bin, Step, Sym, Tape, Un, bin, un};

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
    /// The program of `root`, recorded on `tape`, whose variable `i` is input `slots[i]`: the
    /// steps `root` reads, each once, in the tape's order.
    pub fn compile(tape: &Tape, root: Sym, slots: &[usize]) -> Self {
        let steps = &tape.steps;
        // Which steps the value reads: the tape backwards, each step marking what it reads.
        let mut live = vec![false; steps.len()];
        let mark = |live: &mut [bool], s: Sym| {
            if let Sym::Step(i) = s
                && let Some(l) = live.get_mut(i as usize)
            {
                *l = true;
            }
        };
        mark(&mut live, root);
        for i in (0..steps.len()).rev() {
            if live[i] {
                match steps[i] {
                    Step::Un(_, a) => mark(&mut live, a),
                    Step::Bin(_, a, b) => {
                        mark(&mut live, a);
                        mark(&mut live, b);
                    }
                }
            }
        }
        let mut p = Self { code: Vec::new() };
        // The register of each live step, and of each input once read.
        let mut register = vec![u32::MAX; steps.len()];
        let mut inputs: Vec<(usize, u32)> = Vec::new();
        let mut operand = |p: &mut Self, register: &[u32], s: Sym| -> u32 {
            match s {
                Sym::Num(x) => p.push(Instr::Num(x)),
                Sym::Var(i) => {
                    let slot = slots.get(i).copied().unwrap_or(usize::MAX);
                    if let Some(&(_, r)) = inputs.iter().find(|(k, _)| *k == slot) {
                        r
                    } else {
                        let r = p.push(Instr::Input(slot));
                        inputs.push((slot, r));
                        r
                    }
                }
                Sym::Step(i) => register.get(i as usize).copied().unwrap_or(u32::MAX),
            }
        };
        for (i, step) in steps.iter().enumerate() {
            if !live[i] {
                continue;
            }
            let instr = match *step {
                Step::Un(op, a) => Instr::Un(op, operand(&mut p, &register, a)),
                Step::Bin(op, a, b) => {
                    let a = operand(&mut p, &register, a);
                    let b = operand(&mut p, &register, b);
                    Instr::Bin(op, a, b)
                }
            };
            register[i] = p.push(instr);
        }
        // The value is the last instruction: the root's step is the last live one (a step reads
        // only earlier ones), and a number or an input is all there is.
        if !matches!(root, Sym::Step(_)) {
            operand(&mut p, &register, root);
        }
        p
    }

    fn push(&mut self, instr: Instr) -> u32 {
        self.code.push(instr);
        (self.code.len() - 1) as u32
    }

    /// How many instructions the program runs.
    #[must_use]
    pub fn len(&self) -> usize {
        self.code.len()
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
