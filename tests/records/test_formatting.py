"""The one formatter of numbers and model names (src/chainchaos/records/formatting.py)."""

import math

import numpy as np

from chainchaos.records.formatting import (
    plain_number,
    round_significant,
    tex_escape,
    tex_math,
    tex_number,
    tex_parameter,
    tex_scientific,
)


def test_measured_numbers_have_three_significant_digits_and_powers_of_ten_outside_the_plain_range():
    assert tex_number(2.694) == "2.69" and tex_number(26.94) == "26.9" and tex_number(0.01234) == "0.0123"
    assert tex_number(1e-3) == r"10^{-3}" and tex_number(2.5e-7, 2) == r"2.5\times 10^{-7}"
    assert tex_number(9.996e4) == r"10^{5}"  # the mantissa rounds up to 10
    assert tex_number(12345.0) == r"1.23\times 10^{4}"
    assert tex_number(None) == tex_number(math.nan) == tex_number(math.inf) == "--"
    assert tex_number(True) == "yes" and tex_number(np.bool_(False)) == "no"
    assert tex_number(np.int64(40)) == "40" and tex_number(0.0) == "0"
    assert tex_math(2.694) == "$2.69$" and tex_math(None) == "$--$"


def test_parameters_print_as_typed():
    assert tex_parameter(5e-4) == r"5\times 10^{-4}" and tex_parameter(8.7381) == "8.7381"
    assert tex_parameter(1e5) == r"10^{5}" and tex_parameter(5.0) == "5" and tex_parameter(0.25) == "0.25"


def test_numerics_and_csv_numbers():
    assert tex_scientific(1.2e-5) == r"1.2\times10^{-5}" and tex_scientific(9.96e-3) == r"1.0\times10^{-2}"
    assert tex_scientific(math.nan) == "--"
    assert plain_number(1.87254) == "1.87254" and plain_number(math.nan) == "nan"
    assert plain_number(1.87254, 3, missing="--") == "1.87" and plain_number(math.inf, missing="") == ""
    assert round_significant(1.87254) == 1.87
    assert tex_escape("hertz_H0.25") == r"hertz\_H0.25"


