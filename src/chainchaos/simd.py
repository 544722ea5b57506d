"""Explicit SIMD vectors of ``LANES`` doubles for Numba kernels.

Numba's LLVM vectorises long loops with unit stride, but not a sweep that carries values from one
bond to the next or a loop of 8 lanes (LLVM unrolls it to scalar code: Numba leaves the SLP
vectoriser off). The batch engine therefore writes its lane arithmetic on an explicit vector type:
``vload(a, i)`` reads a[i:i+LANES] as one ``<LANES x double>`` register, ``vstore(a, i, v)``
writes it back, and ``+ - *`` (vector with vector or with a float, which is broadcast),
``max(v, x)`` and ``np.sqrt(v)`` act lane by lane. Each lane gets exactly the IEEE operation its
scalar expression would (no fused multiply-add, no reassociation), so the force laws of
``chainchaos.models``, written for floats, compile unchanged for vectors and give bit-identical
results. LLVM lowers a vector of 8 doubles to one AVX-512 register, two AVX2 registers or four
SSE2 registers, so the code runs on any x86-64 (and other) CPU.

``i`` is an element index (not bytes); the caller keeps i + LANES within the array: there is no
bounds check. Loads and stores assume only the alignment of a double.
"""

import operator

import numpy as np
from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic, models, overload, register_model

#: Doubles per vector: one AVX-512 register.
LANES = 8

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
