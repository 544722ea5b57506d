"""Explicit SIMD vectors of ``LANES`` doubles for Numba kernels.

Numba's LLVM vectorises long loops with unit stride, but not a sweep that carries values from one
bond to the next or a loop of 8 lanes (LLVM unrolls it to scalar code: Numba leaves the SLP
vectoriser off). The batch engine therefore writes its lane arithmetic on an explicit vector type:
``vload(a, i)`` reads a[i:i+LANES] as one ``<LANES x double>`` register, ``vstore(a, i, v)``
writes it back, and ``+ - *`` (vector with vector or with a float, which is broadcast),
``max(v, x)``, ``np.sqrt(v)`` and ``np.expm1(v)`` act lane by lane. Each lane gets exactly the
IEEE operation (or C library call) its scalar expression would (no fused multiply-add, no
reassociation), so the bond laws of ``chainchaos.system.models``, written for floats, compile unchanged
for vectors and give bit-identical results.

The width is fitted to the CPU the kernels are compiled for (``target_lanes``): 8 doubles where
LLVM lowers such a vector to one 512-bit register (AVX-512), 4 otherwise (one AVX2 register).
A vector wider than a register is split into several, and a sweep that carries a few vectors from
one bond to the next then runs out of AVX2's 16 registers. ``CHAINCHAOS_SIMD_LANES`` (2, 4 or 8)
selects another width; the result of every lane is the same at every width, to the bit.

``i`` is an element index (not bytes); the caller keeps i + LANES within the array: there is no
bounds check. Loads and stores assume only the alignment of a double.
"""

import operator
import os

import llvmlite.binding as llvm
import numpy as np
from llvmlite import ir
from numba import types
from numba.core import cgutils, config
from numba.core.codegen import get_host_cpu_features
from numba.extending import intrinsic, models, overload, register_model

from chainchaos.errors import require
from chainchaos.kernels.cache import LANES_VARIABLE

ALLOWED_LANES = (2, 4, 8)


def target_has_512_bit_vectors() -> bool:
    """Whether LLVM, compiling for Numba's target CPU (NUMBA_CPU_NAME and NUMBA_CPU_FEATURES, else
    the host), keeps a vector of 8 doubles in one register: asked of LLVM itself, by compiling
    one vector addition, so that a CPU named without its feature list is judged right."""
    llvm.initialize_native_target()  # what Numba does when it first compiles; idempotent
    llvm.initialize_native_asmprinter()
    cpu = config.CPU_NAME or llvm.get_host_cpu_name()
    features = config.CPU_FEATURES if config.CPU_FEATURES is not None else get_host_cpu_features()
    machine = llvm.Target.from_default_triple().create_target_machine(cpu=cpu, features=features)
    module = llvm.parse_assembly(
        "define <8 x double> @add(<8 x double> %a, <8 x double> %b) {\n"
        "  %c = fadd <8 x double> %a, %b\n  ret <8 x double> %c\n}\n")
    return "zmm" in machine.emit_assembly(module)


def target_lanes() -> int:
    """Doubles per vector: ``CHAINCHAOS_SIMD_LANES`` if set, else 8 on a CPU with 512-bit vectors
    and 4 on others."""
    override = os.environ.get(LANES_VARIABLE, "").strip()
    if override:
        require(override in {str(n) for n in ALLOWED_LANES}, LANES_VARIABLE, override,
                f"one of {list(ALLOWED_LANES)}")
        return int(override)
    return 8 if target_has_512_bit_vectors() else 4


#: Doubles per vector, fixed when the package is imported.
LANES = target_lanes()

_DOUBLE = ir.DoubleType()
_VECTOR = ir.VectorType(_DOUBLE, LANES)


class VectorType(types.Type):
    """Numba type of a vector of LANES float64 lanes."""

    def __init__(self):
        super().__init__(name=f"Vector{LANES}xf64")


vector = VectorType()


@register_model(VectorType)
class _VectorModel(models.PrimitiveModel):
    def __init__(self, dmm, fe_type):
        super().__init__(dmm, fe_type, _VECTOR)


def _broadcast(context, builder, value, ty):
    """The vector operand of a binary operation: a vector as is, a number in every lane."""
    if isinstance(ty, VectorType):
        return value
    x = context.cast(builder, value, ty, types.float64)
    lane0 = builder.insert_element(ir.Constant(_VECTOR, ir.Undefined), x, ir.Constant(ir.IntType(32), 0))
    zeros = ir.Constant(ir.VectorType(ir.IntType(32), LANES), [0] * LANES)
    return builder.shuffle_vector(lane0, ir.Constant(_VECTOR, ir.Undefined), zeros)


def _element_pointer(context, builder, array_type, array, index):
    data = context.make_array(array_type)(context, builder, array).data
    return builder.bitcast(builder.gep(data, [index], inbounds=True), _VECTOR.as_pointer())


def _is_float64_array(a):
    return isinstance(a, types.Array) and a.dtype == types.float64 and a.ndim == 1 and a.layout == "C"


@intrinsic
def vload(typingctx, array, index):
    """array[index:index+LANES] as a vector (array: 1-d C-contiguous float64)."""
    if not (_is_float64_array(array) and isinstance(index, types.Integer)):
        return None

    def codegen(context, builder, sig, args):
        return builder.load(_element_pointer(context, builder, sig.args[0], args[0], args[1]), align=8)

    return vector(array, index), codegen


@intrinsic
def vstore(typingctx, array, index, value):
    """array[index:index+LANES] = value."""
    if not (_is_float64_array(array) and isinstance(index, types.Integer) and isinstance(value, VectorType)):
        return None

    def codegen(context, builder, sig, args):
        builder.store(args[2], _element_pointer(context, builder, sig.args[0], args[0], args[1]), align=8)
        return context.get_dummy_value()

    return types.void(array, index, value), codegen


def _operand(t):
    return isinstance(t, VectorType) or isinstance(t, (types.Float, types.Integer))


def _binary_intrinsic(instruction):
    @intrinsic
    def lanewise(typingctx, a, b):
        if not (_operand(a) and _operand(b) and (isinstance(a, VectorType) or isinstance(b, VectorType))):
            return None

        def codegen(context, builder, sig, args):
            x = _broadcast(context, builder, args[0], sig.args[0])
            y = _broadcast(context, builder, args[1], sig.args[1])
            return getattr(builder, instruction)(x, y)

        return vector(a, b), codegen

    return lanewise


def _register_operator(op, lanewise):
    @overload(op)
    def _impl(a, b):
        if isinstance(a, VectorType) or isinstance(b, VectorType):
            return lambda a, b: lanewise(a, b)


for _op, _instruction in ((operator.add, "fadd"), (operator.sub, "fsub"), (operator.mul, "fmul")):
    _register_operator(_op, _binary_intrinsic(_instruction))


@intrinsic
def _maximum(typingctx, a, b):
    def codegen(context, builder, sig, args):
        x = _broadcast(context, builder, args[0], sig.args[0])
        y = _broadcast(context, builder, args[1], sig.args[1])
        # lane by lane what Numba's scalar max(x, y) returns: y if y > x else x
        return builder.select(builder.fcmp_ordered(">", y, x), y, x)

    return vector(a, b), codegen


@overload(max)
def _max(a, b):
    if isinstance(a, VectorType) and _operand(b):
        return lambda a, b: _maximum(a, b)


@intrinsic
def _square_root(typingctx, a):
    def codegen(context, builder, sig, args):
        sqrt = cgutils.get_or_insert_function(builder.module, ir.FunctionType(_VECTOR, [_VECTOR]),
                                              f"llvm.sqrt.v{LANES}f64")
        return builder.call(sqrt, args)

    return vector(a), codegen


@overload(np.sqrt)
def _sqrt(a):
    if isinstance(a, VectorType):
        return lambda a: _square_root(a)


@intrinsic
def _expm1(typingctx, a):
    def codegen(context, builder, sig, args):
        # lane by lane the C library's expm1, the function Numba's scalar np.expm1 calls
        expm1 = cgutils.get_or_insert_function(builder.module, ir.FunctionType(_DOUBLE, [_DOUBLE]), "expm1")
        out = ir.Constant(_VECTOR, ir.Undefined)
        for lane in range(LANES):
            index = ir.Constant(ir.IntType(32), lane)
            out = builder.insert_element(out, builder.call(expm1, [builder.extract_element(args[0], index)]), index)
        return out

    return vector(a), codegen


@overload(np.expm1)
def _expm1_overload(a):
    if isinstance(a, VectorType):
        return lambda a: _expm1(a)


def _window_intrinsic(first: int, doc: str):
    """The LANES consecutive lanes from lane ``first`` of the concatenation (a, b) of two vectors:
    one shuffle in registers instead of an unaligned load of data just stored, which the CPU
    cannot forward from its store buffer."""

    @intrinsic
    def window(typingctx, a, b):
        if not (isinstance(a, VectorType) and isinstance(b, VectorType)):
            return None

        def codegen(context, builder, sig, args):
            mask = ir.Constant(ir.VectorType(ir.IntType(32), LANES), list(range(first, first + LANES)))
            return builder.shuffle_vector(args[0], args[1], mask)

        return vector(a, b), codegen

    window.__doc__ = doc
    return window


vnext = _window_intrinsic(1, "vnext(a, b) = (a[1], ..., a[LANES-1], b[0]): with a = x[i:i+LANES] and "
                             "b = x[i+LANES:i+2*LANES], x[i+1:i+1+LANES].")
vprev = _window_intrinsic(LANES - 1, "vprev(a, b) = (a[LANES-1], b[0], ..., b[LANES-2]): with "
                                     "a = x[i-LANES:i] and b = x[i:i+LANES], x[i-1:i-1+LANES].")


@intrinsic
def vbelow(typingctx, a, b):
    """1.0 in the lanes where a < b, else 0.0 (NaN compares false): a count that adds up in a
    vector (a or b a vector, the other a vector or a number)."""
    if not (_operand(a) and _operand(b) and (isinstance(a, VectorType) or isinstance(b, VectorType))):
        return None

    def codegen(context, builder, sig, args):
        x = _broadcast(context, builder, args[0], sig.args[0])
        y = _broadcast(context, builder, args[1], sig.args[1])
        one, zero = ir.Constant(_VECTOR, [1.0] * LANES), ir.Constant(_VECTOR, [0.0] * LANES)
        return builder.select(builder.fcmp_ordered("<", x, y), one, zero)

    return vector(a, b), codegen
