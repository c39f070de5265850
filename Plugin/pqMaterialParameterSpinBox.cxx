#include "pqMaterialParameterSpinBox.h"

#include "mmvNumberText.h"

#include <QLineEdit>

namespace
{
mmv::NumberText parse(const QString& text, double min, double max)
{
  return mmv::ParseNumberText(text.toStdString(), min, max);
}
}

//-----------------------------------------------------------------------------
pqMaterialParameterSpinBox::pqMaterialParameterSpinBox(QWidget* parent)
  : QDoubleSpinBox(parent)
{
  // Text the parser refuses at the end reverts to the last accepted value.
  this->setCorrectionMode(QAbstractSpinBox::CorrectToPreviousValue);
}

//-----------------------------------------------------------------------------
QValidator::State pqMaterialParameterSpinBox::validate(QString& text, int&) const
{
  const mmv::NumberTextState state = parse(text, this->minimum(), this->maximum()).State;
  if (state == mmv::NumberTextState::Invalid && this->Refused)
  {
    // Qt drops the keystroke; without this it would vanish without a word.
    this->Refused(text);
  }
  switch (state)
  {
    case mmv::NumberTextState::Acceptable:
      return QValidator::Acceptable;
    case mmv::NumberTextState::Intermediate:
    // Out of range while typing may still be on its way ("1" of "0.1" is
    // fine, "-" too); fixup() refuses it if editing ends there.
    case mmv::NumberTextState::OutOfRange:
      return QValidator::Intermediate;
    case mmv::NumberTextState::Invalid:
    default:
      return QValidator::Invalid;
  }
}

//-----------------------------------------------------------------------------
double pqMaterialParameterSpinBox::valueFromText(const QString& text) const
{
  const mmv::NumberText parsed = parse(text, this->minimum(), this->maximum());
  return parsed.State == mmv::NumberTextState::Acceptable ? parsed.Value : this->value();
}

//-----------------------------------------------------------------------------
QString pqMaterialParameterSpinBox::textFromValue(double value) const
{
  return QString::number(value, 'f', this->decimals());
}

//-----------------------------------------------------------------------------
void pqMaterialParameterSpinBox::fixup(QString& text) const
{
  const mmv::NumberText parsed = parse(text, this->minimum(), this->maximum());
  if (parsed.State == mmv::NumberTextState::OutOfRange && this->Refused)
  {
    this->Refused(text);
  }
  // CorrectToPreviousValue then restores the last accepted value.
}

//-----------------------------------------------------------------------------
void pqMaterialParameterSpinBox::setNormalToolTip(const QString& tip)
{
  this->NormalToolTip = tip;
  if (this->Problem.isEmpty())
  {
    this->setToolTip(tip);
  }
}

//-----------------------------------------------------------------------------
void pqMaterialParameterSpinBox::setProblem(const QString& why)
{
  if (why == this->Problem)
  {
    return;
  }
  this->Problem = why;
  this->setToolTip(why.isEmpty() ? this->NormalToolTip : why);
  this->setStyleSheet(
    why.isEmpty() ? QString() : QStringLiteral("QDoubleSpinBox { border: 2px solid red; }"));
}
