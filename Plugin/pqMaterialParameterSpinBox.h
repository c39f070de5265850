/**
 * @class   pqMaterialParameterSpinBox
 * @brief   Spin box of the Multi-Material Editor: reads fixed and exponent
 *          notation ("2.5e-1", "1e3") with mmv::ParseNumberText, and refuses
 *          a value outside its range visibly (red border, tooltip, and the
 *          Refused callback) instead of silently keeping part of the text.
 *
 * QDoubleSpinBox drops characters its validator does not expect, so "1e9"
 * typed into Shininess would become 19.
 */
#ifndef pqMaterialParameterSpinBox_h
#define pqMaterialParameterSpinBox_h

#include <QDoubleSpinBox>
#include <QString>

#include <functional>

class pqMaterialParameterSpinBox : public QDoubleSpinBox
{
public:
  explicit pqMaterialParameterSpinBox(QWidget* parent = nullptr);

  QValidator::State validate(QString& text, int& pos) const override;
  double valueFromText(const QString& text) const override;
  /// Always with a '.' (the parser is locale-independent, so the text must be).
  QString textFromValue(double value) const override;
  void fixup(QString& text) const override;

  /// Marks the box as holding a problem (red border, `why` as tooltip) or,
  /// with an empty `why`, clears the mark and restores the normal tooltip.
  void setProblem(const QString& why);
  bool hasProblem() const { return !this->Problem.isEmpty(); }

  /// Called with the text when typed text is refused: a keystroke that
  /// cannot make a number ("nan"), or a number out of range when editing ends.
  std::function<void(const QString&)> Refused;

  /// The tooltip shown when there is no problem.
  void setNormalToolTip(const QString& tip);

private:
  QString NormalToolTip;
  QString Problem;
};

#endif
