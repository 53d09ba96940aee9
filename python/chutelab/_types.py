"""Small typed values the package returns: a quantity's names for plotting, an effect's strength."""

from dataclasses import dataclass
from typing import Optional


@dataclass(frozen=True)
class Quantity:
    """One quantity of the tables' `quantity` column, for axis labels.

    name: as in the tables ("normal_force_N"); symbol: the reference study's ("R_n");
    label: words ("plate normal force"); unit: the tables' unit ("N")."""

    name: str
    symbol: str
    label: str
    unit: str

    @property
    def axis_label(self) -> str:
        """"plate normal force R_n [N]": label, symbol and unit for a plot's axis."""
        return f"{self.label} {self.symbol} [{self.unit}]"


@dataclass(frozen=True)
class Strength:
    """An effect's strength: value ± sd in unit.

    effect: the effect's name ("air_drag"); parameter: its strength parameter
    ("drag_coefficient"); value and sd (one standard deviation; None when the value was given,
    not fitted) in unit ("" = dimensionless); fitted: whether it was calibrated on the data."""

    effect: str
    parameter: str
    value: float
    sd: Optional[float]
    unit: str
    fitted: bool

    def __str__(self) -> str:
        unit = f" {self.unit}" if self.unit else ""
        pm = f" ± {self.sd:.2g}" if self.sd is not None else ""
        how = "fitted" if self.fitted else "given"
        return f"{self.effect}: {self.parameter} = {self.value:.4g}{pm}{unit} ({how})"
