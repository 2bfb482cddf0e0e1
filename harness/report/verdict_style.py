"""How a calibration verdict (within, conservative, liberal) looks: its terminal colour, its page class, and
the key that explains the colours under tables and on pages."""

#: Terminal colour and page class of each verdict, and what the colours mean (under tables, on pages).
VERDICT_COLOUR = {"within": "green", "conservative": "yellow", "liberal": "red"}
VERDICT_CLASS = {"within": "pass", "conservative": "warn", "liberal": "fail"}
VERDICT_KEY = ("green: the nominal level is inside the interval; yellow: the interval lies below it (conservative: "
               "fewer false alarms than stated, which passes); red: above it (liberal, which fails)")
