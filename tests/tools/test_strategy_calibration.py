"""The strategy calibration script's figures: null rates with their intervals, and the power line."""
from tools import strategy_calibration as cal
from tools.strategy_triples import UNIFORM


def test_null_rates_give_a_line_per_level():
    lines = cal.null_rates(list(cal.synthetic(4)), cal.SYNTHETIC_SPP)
    assert len(lines) == 3 and lines[0].startswith("  level 0.3   false alarms ") and "/4 = " in lines[0]

def test_power_stops_at_the_first_bias_named_most_of_the_time(monkeypatch):
    monkeypatch.setattr(cal, "PLANTS", (("mats", UNIFORM),))
    monkeypatch.setattr(cal, "BIASES", (0.001, 0.5, 0.6))
    (line,) = cal.power(list(cal.synthetic(3)), cal.SYNTHETIC_SPP)
    assert line == "  mats x (1 + b uniform) named 90% of the time from b = 0.5 (0.001: 0.00, 0.5: 1.00)"
