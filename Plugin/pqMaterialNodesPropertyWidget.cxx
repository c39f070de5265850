#include "pqMaterialNodesPropertyWidget.h"

#include "mmvMaterialNodeModel.h"
#include "mmvNumberText.h"
#include "pqDoubleLineEdit.h"
#include "pqMaterialNodesTrack.h"
#include "pqMaterialParameterSpinBox.h"
#include "pqPropertiesPanel.h"

#include "vtkCommand.h"
#include "vtkEventQtSlotConnect.h"
#include "vtkMaterialLibrary.h"
#include "vtkMultiMaterialParameters.h"
#include "vtkNew.h"
#include "vtkPVArrayInformation.h"
#include "vtkPVDataInformation.h"
#include "vtkPVLogger.h"
#include "vtkSMProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMRepresentationProxy.h"
#include "vtkSMStringVectorProperty.h"
#include "vtkWeakPointer.h"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QIcon>
#include <QImage>
#include <QLabel>
#include <QPixmap>
#include <QResizeEvent>
#include <QStringList>
#include <QStyle>
#include <QTextStream>
#include <QToolButton>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace
{
constexpr int Stride = mmv::MaterialNodeModel::Stride;
constexpr int ParameterCount = mmv::MaterialNodeModel::ParameterCount;

QString parameterLabel(int p)
{
  QString key = QString::fromLatin1(mmv::MaterialParameterTable[p].Key);
  key[0] = key[0].toUpper();
  // transmission_r reads "Transmission r".
  return key.replace(QLatin1Char('_'), QLatin1Char(' '));
}

// The editor's row label. ParaView's Volume representation shows its own
// "Specular" (Lighting group) in the same panel, so ours says whose it is.
QString editorLabel(int p)
{
  return p == mmv::Specular ? pqMaterialNodesPropertyWidget::tr("Material Specular")
                            : parameterLabel(p);
}

// A preset's swatch: a grey sphere shaded with the preset's ambient,
// diffuse, specular and shininess (Blinn-Phong, light from the upper left).
// Grey, because a preset sets the material, never the colour: that comes
// from the colour map, and a coloured swatch would promise one.
QPixmap presetSwatch(const double parameters[ParameterCount], int size)
{
  QImage image(size, size, QImage::Format_ARGB32);
  image.fill(Qt::transparent);
  const double light[3] = { -0.48, -0.55, 0.68 }; // y down, towards the viewer
  const double norm = std::sqrt(light[0] * light[0] + light[1] * light[1] + light[2] * light[2]);
  const double l[3] = { light[0] / norm, light[1] / norm, light[2] / norm };
  double h[3] = { l[0], l[1], l[2] + 1.0 };
  const double hn = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
  const double albedo = 0.75;
  for (int y = 0; y < size; ++y)
  {
    for (int x = 0; x < size; ++x)
    {
      const double nx = (x + 0.5) / size * 2.0 - 1.0;
      const double ny = (y + 0.5) / size * 2.0 - 1.0;
      const double r2 = nx * nx + ny * ny;
      if (r2 > 1.0)
      {
        continue;
      }
      const double nz = std::sqrt(1.0 - r2);
      const double ndotl = std::max(0.0, nx * l[0] + ny * l[1] + nz * l[2]);
      const double ndoth = std::max(0.0, (nx * h[0] + ny * h[1] + nz * h[2]) / hn);
      const double shade = albedo * (parameters[mmv::Ambient] + parameters[mmv::Diffuse] * ndotl) +
        (ndotl > 0.0 ? parameters[mmv::Specular] * std::pow(ndoth, parameters[mmv::Shininess])
                     : 0.0);
      const int grey = static_cast<int>(std::round(255.0 * std::min(1.0, shade)));
      image.setPixel(x, y, qRgba(grey, grey, grey, 255));
    }
  }
  return QPixmap::fromImage(image);
}

// What a preset sets, for its tooltip.
QString presetDescription(const char* name, const double parameters[ParameterCount])
{
  QStringList values;
  for (int p = 0; p < ParameterCount; ++p)
  {
    values << QStringLiteral("%1 %2")
                .arg(QString::fromLatin1(mmv::MaterialParameterTable[p].Key))
                .arg(parameters[p]);
  }
  return pqMaterialNodesPropertyWidget::tr(
    "%1 sets the material only (%2); colour and opacity stay those of the colour map.")
    .arg(QString::fromUtf8(name))
    .arg(values.join(", "));
}

bool validRange(const double r[2])
{
  return std::isfinite(r[0]) && std::isfinite(r[1]) && r[1] > r[0];
}
}

//-----------------------------------------------------------------------------
class pqMaterialNodesPropertyWidget::pqInternals
{
public:
  mmv::MaterialNodeModel Model;
  QString Preset; // MaterialPreset: a preset name, or "Custom" (the nodes apply)
  bool HasPresetProperty = false;
  QString CustomPreset = QStringLiteral("Custom"); // MaterialPreset's "use the nodes" value
  int ShownParameter = mmv::Diffuse;               // parameter whose curve the track draws

  bool HasDataRange = false;
  double DataRange[2] = { 0, 1 };

  vtkNew<vtkEventQtSlotConnect> VTKConnect;
  vtkWeakPointer<vtkSMProxy> OpacityProxy;

  pqMaterialNodesTrack* Track = nullptr;
  pqDoubleLineEdit* Value = nullptr;
  pqMaterialParameterSpinBox* Spin[ParameterCount] = {};
  QComboBox* Presets = nullptr;
  QToolButton* Remove = nullptr;
  QLabel* Status = nullptr;
  QString Refusal;          // the last typed value a spin box refused
  QLabel* Notice = nullptr; // shows the model's load problems or Refusal, in red
  QString NoticeText;       // the whole notice (the label may show it elided)
  QGridLayout* Grid = nullptr;
  std::vector<std::pair<QLabel*, QWidget*>> Rows; // Value, then the parameters
  int Columns = 0;                                // label/editor pairs per grid row
  bool Updating = false;                          // editors being filled from the nodes

  // Numbers MaterialNodes held that the renderer rejects, as loaded: the
  // editors show the model's stand-ins (never a NaN clamped to 1000) and
  // mark them, and the next edit writes the stand-in, never the bad number,
  // back.
  QStringList loadProblems() const
  {
    QStringList text;
    for (const auto& problem : this->Model.GetLoadProblems())
    {
      if (problem.Parameter < 0)
      {
        text
          << pqMaterialNodesPropertyWidget::tr("a node at value %1 is left out").arg(problem.Value);
      }
      else
      {
        text << pqMaterialNodesPropertyWidget::tr("node %1: %2; shown as %3")
                  .arg(problem.Node + 1)
                  .arg(QString::fromStdString(problem.Why))
                  .arg(problem.Shown);
      }
    }
    return text;
  }

  // The notice row is always there, one line high, so a notice never moves
  // the fields below it; a long notice is elided and whole in the tooltip.
  void showNotice()
  {
    QString text = this->Refusal;
    const QStringList problems = this->loadProblems();
    if (!problems.isEmpty())
    {
      text = pqMaterialNodesPropertyWidget::tr(
        "MaterialNodes holds invalid numbers, so the renderer ignores it: %1. The editor shows "
        "stand-ins (red); your next edit applies them.")
               .arg(problems.join("; "));
    }
    this->NoticeText = text;
    this->Notice->setToolTip(text);
    this->elideNotice();
  }

  void elideNotice()
  {
    const int width = std::max(20, this->Notice->contentsRect().width());
    this->Notice->setText(
      this->Notice->fontMetrics().elidedText(this->NoticeText, Qt::ElideRight, width));
  }

  // The representation shades with MaterialPreset instead of the nodes.
  bool presetActive() const
  {
    return this->HasPresetProperty && !this->Preset.isEmpty() &&
      this->Model.GetLibrary()->HasPreset(this->Preset.toUtf8().constData());
  }

  // The colour map's range, as the representation spreads a preset over it
  // (vtkPVMultiMaterialVolumeRepresentation::UpdateMapperParameters).
  static void colorMapRange(vtkSMProxy* repr, double range[2])
  {
    range[0] = 0.0;
    range[1] = 1.0;
    vtkSMProxy* lut = repr->GetProperty("LookupTable")
      ? vtkSMPropertyHelper(repr, "LookupTable", true).GetAsProxy()
      : nullptr;
    if (lut && lut->GetProperty("RGBPoints"))
    {
      vtkSMPropertyHelper points(lut, "RGBPoints");
      const unsigned int n = points.GetNumberOfElements();
      if (n >= 4)
      {
        range[0] = points.GetAsDouble(0);
        range[1] = points.GetAsDouble(n - 4);
      }
    }
    if (!(range[1] > range[0]))
    {
      range[1] = range[0] + 1.0;
    }
  }

  // The load problem of the selected node's parameter `p`, or "".
  QString cellProblem(int p) const
  {
    return this->Model.IsStandIn(this->Model.GetCurrent(), p)
      ? pqMaterialNodesPropertyWidget::tr(
          "MaterialNodes held an invalid number here (the renderer ignored the list); this "
          "shows a stand-in, written back with your next edit.")
      : QString();
  }

  // What the track needs besides the model.
  void updateTrack()
  {
    auto& view = this->Track->viewState();
    view.ShownParameter = this->ShownParameter;
    view.ActivePreset = this->presetActive() ? this->Preset : QString();
    this->Track->update();
  }
};

//-----------------------------------------------------------------------------
pqMaterialNodesPropertyWidget::pqMaterialNodesPropertyWidget(
  vtkSMProxy* smproxy, vtkSMProperty* smproperty, QWidget* parentObject)
  : Superclass(smproxy, parentObject)
  , Internals(new pqInternals())
{
  auto& internals = *this->Internals;
  // The track and the form are wider than the label column allows.
  this->setShowLabel(false);

  auto* vbox = new QVBoxLayout(this);
  vbox->setMargin(pqPropertiesPanel::suggestedMargin());
  vbox->setSpacing(pqPropertiesPanel::suggestedVerticalSpacing());

  internals.Track = new pqMaterialNodesTrack(this, internals.Model);
  vbox->addWidget(internals.Track);

  // Preset chooser, selection status and remove button on one row.
  vbox->addLayout(this->createSelectionRow());
  internals.Notice = new QLabel(this);
  internals.Notice->setObjectName("Notice");
  internals.Notice->setWordWrap(false);
  internals.Notice->setStyleSheet(QStringLiteral("QLabel { color: #d02020; }"));
  internals.Notice->setFixedHeight(internals.Notice->fontMetrics().lineSpacing());
  internals.Notice->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Fixed);
  vbox->addWidget(internals.Notice);

  // The selected node: its value and the parameters, two per row.
  this->createEditors();
  this->layoutEditors(1);
  vbox->addLayout(internals.Grid);

  QObject::connect(internals.Value, &pqDoubleLineEdit::textChangedAndEditingFinished, this,
    &pqMaterialNodesPropertyWidget::onValueEdited);
  QObject::connect(internals.Presets, QOverload<int>::of(&QComboBox::activated), this,
    &pqMaterialNodesPropertyWidget::onPresetActivated);
  QObject::connect(internals.Remove, &QToolButton::clicked, this,
    &pqMaterialNodesPropertyWidget::removeCurrentNode);

  // Links pull the current values into the widget now and keep it in step
  // with undo/redo, Python and state files later.
  this->addPropertyLink(this, "materialNodes", SIGNAL(materialNodesChanged()), smproperty);
  if (vtkSMProperty* preset = smproxy->GetProperty("MaterialPreset"))
  {
    internals.HasPresetProperty = true;
    // The property's default is its "use the nodes" entry.
    auto* svp = vtkSMStringVectorProperty::SafeDownCast(preset);
    if (svp && svp->GetDefaultValue(0))
    {
      internals.CustomPreset = QString::fromUtf8(svp->GetDefaultValue(0));
    }
    this->addPropertyLink(this, "materialPreset", SIGNAL(materialPresetChanged()), preset);
  }

  // The track's range and opacity curve follow the data and the colouring.
  internals.VTKConnect->Connect(
    smproxy, vtkCommand::PropertyModifiedEvent, this, SLOT(updateContext()));
  internals.VTKConnect->Connect(smproxy, vtkCommand::UpdateDataEvent, this, SLOT(updateContext()));
  this->updateContext();
  this->updateEditors();

  vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(),
    "pqMaterialNodesPropertyWidget created with %d nodes", this->nodeCount());
}

//-----------------------------------------------------------------------------
QHBoxLayout* pqMaterialNodesPropertyWidget::createSelectionRow()
{
  auto& internals = *this->Internals;
  auto* row = new QHBoxLayout();
  row->setSpacing(pqPropertiesPanel::suggestedHorizontalSpacing());
  internals.Presets = new QComboBox(this);
  internals.Presets->setObjectName("Presets");
  internals.Presets->setToolTip(tr("Applies a material preset (shading parameters, not colour: "
                                   "colour comes from the colour map) to the selected node, or to "
                                   "the whole range when no node is selected."));
  internals.Presets->addItem(tr("Apply material preset..."));
  const int swatch = this->style()->pixelMetric(QStyle::PM_SmallIconSize);
  vtkMaterialLibrary* library = internals.Model.GetLibrary();
  for (int i = 0; i < library->GetNumberOfPresets(); ++i)
  {
    const char* name = library->GetPresetName(i);
    double parameters[ParameterCount];
    if (!library->GetPreset(name, parameters))
    {
      continue;
    }
    internals.Presets->addItem(QIcon(presetSwatch(parameters, swatch)), QString::fromUtf8(name));
    internals.Presets->setItemData(
      internals.Presets->count() - 1, presetDescription(name, parameters), Qt::ToolTipRole);
  }
  row->addWidget(internals.Presets, 1);
  internals.Status = new QLabel(this);
  internals.Status->setObjectName("Status");
  row->addWidget(internals.Status);
  internals.Remove = new QToolButton(this);
  internals.Remove->setObjectName("RemoveNode");
  internals.Remove->setIcon(this->style()->standardIcon(QStyle::SP_DialogDiscardButton));
  internals.Remove->setToolTip(tr("Remove the selected node (Delete)"));
  internals.Remove->setAutoRaise(true);
  row->addWidget(internals.Remove);
  return row;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::createEditors()
{
  auto& internals = *this->Internals;
  internals.Grid = new QGridLayout();
  internals.Grid->setHorizontalSpacing(pqPropertiesPanel::suggestedHorizontalSpacing());
  internals.Grid->setVerticalSpacing(pqPropertiesPanel::suggestedVerticalSpacing());
  internals.Value = new pqDoubleLineEdit(this);
  internals.Value->setObjectName("Value");
  internals.Value->setToolTip(tr("Data value of the selected node"));
  internals.Rows.emplace_back(new QLabel(tr("Value"), this), internals.Value);
  for (int p = 0; p < ParameterCount; ++p)
  {
    const mmv::MaterialParameterInfo& info = mmv::MaterialParameterTable[p];
    auto* spin = new pqMaterialParameterSpinBox(this);
    spin->setObjectName(QString::fromLatin1(info.Key));
    // The spin box accepts everything the renderer accepts; the soft range
    // only sets the step, so typical values are a few clicks apart.
    spin->setRange(info.HardMin, info.HardMax);
    spin->setDecimals(info.SoftMax > 10 ? 1 : 3);
    spin->setSingleStep((info.SoftMax - info.SoftMin) / (info.SoftMax > 10 ? 20.0 : 100.0));
    // Commit on Enter/focus-out/arrows, not on every keystroke: one undo step.
    spin->setKeyboardTracking(false);
    spin->setNormalToolTip(tr("%1 of the selected node (typically %2 to %3, at most %4; "
                              "exponent notation such as 2.5e-1 works)")
                             .arg(parameterLabel(p))
                             .arg(info.SoftMin)
                             .arg(info.SoftMax)
                             .arg(info.HardMax));
    spin->Refused = [&internals, p, spin](const QString& text)
    {
      internals.Refusal = QString::fromStdString(mmv::MaterialNodeModel::ParameterTextNotice(
        p, text.trimmed().toStdString(), spin->value()));
      internals.showNotice();
      vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(), "%s", internals.Refusal.toUtf8().constData());
    };
    internals.Spin[p] = spin;
    auto* label = new QLabel(editorLabel(p), this);
    label->setBuddy(spin);
    internals.Rows.emplace_back(label, spin);
    QObject::connect(spin, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this,
      &pqMaterialNodesPropertyWidget::onParameterEdited);
  }
}

//-----------------------------------------------------------------------------
pqMaterialNodesPropertyWidget::~pqMaterialNodesPropertyWidget() = default;

//-----------------------------------------------------------------------------
QList<QVariant> pqMaterialNodesPropertyWidget::materialNodes() const
{
  QList<QVariant> values;
  for (double v : this->Internals->Model.GetFlat())
  {
    values.push_back(v);
  }
  return values;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::setMaterialNodes(const QList<QVariant>& values)
{
  auto& internals = *this->Internals;
  std::vector<double> flat;
  flat.reserve(values.size());
  for (const QVariant& v : values)
  {
    flat.push_back(v.toDouble());
  }
  internals.Model.SetFlat(flat);
  const QStringList problems = internals.loadProblems();
  if (!problems.isEmpty())
  {
    vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(),
      "MaterialNodes: %d invalid number(s) shown as "
      "stand-ins: %s",
      static_cast<int>(problems.size()), problems.join("; ").toUtf8().constData());
  }
  this->updateEditors();
}

//-----------------------------------------------------------------------------
QString pqMaterialNodesPropertyWidget::materialPreset() const
{
  return this->Internals->Preset;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::setMaterialPreset(const QString& name)
{
  this->Internals->Preset = name;
  this->updateEditors(); // with no selection the editors show the preset
}

//-----------------------------------------------------------------------------
int pqMaterialNodesPropertyWidget::nodeCount() const
{
  return this->Internals->Model.GetNumberOfNodes();
}

//-----------------------------------------------------------------------------
int pqMaterialNodesPropertyWidget::currentNode() const
{
  return this->Internals->Model.GetCurrent();
}

//-----------------------------------------------------------------------------
QString pqMaterialNodesPropertyWidget::nodesText() const
{
  QString text;
  QTextStream stream(&text);
  for (const auto& n : this->Internals->Model.GetNodes())
  {
    stream << n[0] << ":";
    for (int p = 1; p < Stride; ++p)
    {
      stream << " " << n[p];
    }
    stream << "\n";
  }
  return text.trimmed();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::trackRange(double range[2]) const
{
  const auto& internals = *this->Internals;
  internals.Model.TrackRange(internals.HasDataRange ? internals.DataRange : nullptr, range);
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::setCurrentNode(int index)
{
  this->Internals->Model.SetCurrent(index);
  this->updateEditors();
}

//-----------------------------------------------------------------------------
int pqMaterialNodesPropertyWidget::addNode(double value)
{
  bool changed = false;
  const int index = this->insertNode(value, &changed);
  if (changed)
  {
    this->commitNodes();
  }
  return index;
}

//-----------------------------------------------------------------------------
int pqMaterialNodesPropertyWidget::insertNode(double value, bool* changed)
{
  auto& internals = *this->Internals;
  bool fromPreset = false;
  if (internals.presetActive())
  {
    // A node added while a preset shows takes the preset's material there
    // (docs/material-editor.md), not whatever the unused nodes hold;
    // commitNodes() then switches MaterialPreset to Custom.
    double range[2];
    pqInternals::colorMapRange(this->proxy(), range);
    fromPreset =
      internals.Model.TakePreset(internals.Preset.toUtf8().constData(), range[0], range[1]);
  }
  bool inserted = false;
  const int index = internals.Model.Insert(value, &inserted);
  if (changed)
  {
    *changed = fromPreset || inserted;
  }
  this->updateEditors();
  return index;
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::removeCurrentNode()
{
  if (this->Internals->Model.RemoveCurrent())
  {
    this->commitNodes();
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::moveNode(int index, double value, bool commit)
{
  double range[2];
  this->trackRange(range);
  if (!this->Internals->Model.Move(index, value, range))
  {
    return;
  }
  if (commit)
  {
    this->commitNodes();
  }
  else
  {
    this->updateEditors();
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::applyPreset(const QString& name)
{
  auto& internals = *this->Internals;
  const QByteArray key = name.toUtf8();
  double parameters[ParameterCount];
  if (!internals.Model.GetLibrary()->GetPreset(key.constData(), parameters))
  {
    return;
  }
  if (internals.Model.SetCurrentParameters(parameters))
  {
    this->commitNodes();
    return;
  }
  if (internals.HasPresetProperty)
  {
    // The representation spreads the preset over the colour map's range
    // itself (and keeps it there when the range changes); the nodes stay
    // for when the user goes back to them.
    internals.Preset = name;
    vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(), "MaterialPreset set to '%s'", key.constData());
    this->updateEditors();
    Q_EMIT this->materialPresetChanged();
    return;
  }
  // Same result as vtkMaterialTransferFunction::ApplyPreset over the range.
  double range[2];
  this->trackRange(range);
  internals.Model.SetUniform(parameters, range);
  this->commitNodes();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::commitNodes()
{
  auto& internals = *this->Internals;
  // What is written now holds only the stand-ins, so nothing is left to flag.
  internals.Model.ClearLoadProblems();
  internals.Refusal.clear();
  this->updateEditors();
  vtkVLogF(
    PARAVIEW_LOG_APPLICATION_VERBOSITY(), "MaterialNodes edited: %d nodes", this->nodeCount());
  // The property links turn these into property changes (changeAvailable,
  // then one changeFinished: the panel applies them as one undoable step).
  Q_EMIT this->materialNodesChanged();
  if (internals.presetActive())
  {
    // Editing nodes means using them: a whole-range preset would hide the edit.
    internals.Preset = internals.CustomPreset;
    internals.updateTrack();
    Q_EMIT this->materialPresetChanged();
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::onParameterEdited()
{
  auto& internals = *this->Internals;
  if (internals.Updating || !internals.Model.HasCurrent())
  {
    return;
  }
  for (int p = 0; p < ParameterCount; ++p)
  {
    if (this->sender() == internals.Spin[p])
    {
      internals.Model.SetParameter(internals.Model.GetCurrent(), p, internals.Spin[p]->value());
      internals.ShownParameter = p; // show the curve being edited
      this->commitNodes();
      return;
    }
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::onValueEdited()
{
  auto& internals = *this->Internals;
  if (internals.Updating || !internals.Model.HasCurrent())
  {
    return;
  }
  // The model's parser, as the spin boxes': "nan" or "inf" would pass
  // toDouble(); a value past a neighbour is moved, and both are noticed.
  double range[2];
  this->trackRange(range);
  const bool moved = internals.Model.SetValueText(
    internals.Model.GetCurrent(), internals.Value->text().toStdString(), range);
  const QString notice = QString::fromStdString(internals.Model.GetNotice());
  if (moved)
  {
    this->commitNodes();
  }
  internals.Refusal = notice;
  if (!notice.isEmpty())
  {
    vtkVLogF(PARAVIEW_LOG_APPLICATION_VERBOSITY(), "%s", notice.toUtf8().constData());
  }
  this->updateEditors(); // the node's value as placed, and the notice
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::onPresetActivated(int index)
{
  auto& internals = *this->Internals;
  if (index > 0)
  {
    this->applyPreset(internals.Presets->itemText(index));
  }
  // The combo is an action menu, not a state: back to its prompt.
  internals.Presets->setCurrentIndex(0);
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::updateEditors()
{
  auto& internals = *this->Internals;
  const int current = internals.Model.GetCurrent();
  const bool selected = current >= 0;
  const bool prev = internals.Updating;
  internals.Updating = true;
  internals.Value->setEnabled(selected);
  internals.Remove->setEnabled(selected);
  // With no selection the editors show what shades the whole range: the
  // active preset's material, else the defaults a new node would get.
  double shown[ParameterCount];
  const bool preset = !selected && internals.presetActive() &&
    internals.Model.GetLibrary()->GetPreset(internals.Preset.toUtf8().constData(), shown);
  for (int p = 0; p < ParameterCount; ++p)
  {
    internals.Spin[p]->setEnabled(selected);
    internals.Spin[p]->setValue(selected ? internals.Model.GetNodes()[current][p + 1]
        : preset                         ? shown[p]
                                         : mmv::MaterialParameterTable[p].Default);
    internals.Spin[p]->setProblem(selected ? internals.cellProblem(p) : QString());
  }
  internals.showNotice();
  internals.Value->setText(selected ? pqDoubleLineEdit::formatDoubleUsingGlobalPrecisionAndNotation(
                                        internals.Model.GetNodes()[current][0])
                                    : QString());
  internals.Status->setText(selected ? tr("%1 / %2").arg(current + 1).arg(this->nodeCount())
      : preset                       ? tr("preset %1").arg(internals.Preset)
                                     : tr("%n node(s)", nullptr, this->nodeCount()));
  internals.Updating = prev;
  internals.updateTrack();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::updateContext()
{
  auto& internals = *this->Internals;
  vtkSMProxy* smproxy = this->proxy();

  // Data range of the coloured array, as the representation sees it.
  internals.HasDataRange = false;
  auto* repr = vtkSMRepresentationProxy::SafeDownCast(smproxy);
  if (repr && smproxy->GetProperty("ColorArrayName"))
  {
    vtkSMPropertyHelper colorArray(smproxy, "ColorArrayName");
    const char* name = colorArray.GetInputArrayNameToProcess();
    vtkPVDataInformation* dataInfo = repr->GetRepresentedDataInformation();
    vtkPVArrayInformation* arrayInfo = (name && *name && dataInfo)
      ? dataInfo->GetArrayInformation(name, colorArray.GetInputArrayAssociation())
      : nullptr;
    if (arrayInfo)
    {
      // Magnitude for vectors, which is what volume mapping uses by default.
      arrayInfo->GetComponentRange(
        arrayInfo->GetNumberOfComponents() == 1 ? 0 : -1, internals.DataRange);
      internals.HasDataRange = validRange(internals.DataRange);
    }
  }
  // No data information yet (or no array): the colour map's range.
  vtkSMProxy* lut = smproxy->GetProperty("LookupTable")
    ? vtkSMPropertyHelper(smproxy, "LookupTable", true).GetAsProxy()
    : nullptr;
  if (!internals.HasDataRange && lut && lut->GetProperty("RGBPoints"))
  {
    vtkSMPropertyHelper points(lut, "RGBPoints");
    const unsigned int n = points.GetNumberOfElements();
    if (n >= 8)
    {
      internals.DataRange[0] = points.GetAsDouble(0);
      internals.DataRange[1] = points.GetAsDouble(n - 4);
      internals.HasDataRange = validRange(internals.DataRange);
    }
  }

  // The opacity function this representation uses; follow it when it changes.
  vtkSMProxy* opacity = smproxy->GetProperty("ScalarOpacityFunction")
    ? vtkSMPropertyHelper(smproxy, "ScalarOpacityFunction", true).GetAsProxy()
    : nullptr;
  if (opacity != internals.OpacityProxy)
  {
    if (internals.OpacityProxy)
    {
      internals.VTKConnect->Disconnect(internals.OpacityProxy);
    }
    internals.OpacityProxy = opacity;
    if (opacity)
    {
      internals.VTKConnect->Connect(
        opacity, vtkCommand::PropertyModifiedEvent, this, SLOT(updateContext()));
    }
  }
  auto& opacityCurve = internals.Track->viewState().Opacity;
  opacityCurve.clear();
  if (opacity && opacity->GetProperty("Points"))
  {
    // (x, opacity, midpoint, sharpness) per point; midpoint and sharpness
    // are drawn as straight segments, which is close enough for context.
    vtkSMPropertyHelper points(opacity, "Points");
    const unsigned int n = points.GetNumberOfElements();
    for (unsigned int i = 0; i + 3 < n; i += 4)
    {
      opacityCurve.emplace_back(points.GetAsDouble(i), points.GetAsDouble(i + 1));
    }
  }
  internals.updateTrack();
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::layoutEditors(int columns)
{
  auto& internals = *this->Internals;
  if (columns == internals.Columns)
  {
    return;
  }
  internals.Columns = columns;
  for (auto& row : internals.Rows)
  {
    internals.Grid->removeWidget(row.first);
    internals.Grid->removeWidget(row.second);
  }
  for (int i = 0; i < static_cast<int>(internals.Rows.size()); ++i)
  {
    const int r = i / columns;
    const int c = (i % columns) * 2;
    internals.Grid->addWidget(internals.Rows[i].first, r, c);
    internals.Grid->addWidget(internals.Rows[i].second, r, c + 1);
  }
  for (int c = 0; c < 4; ++c)
  {
    internals.Grid->setColumnStretch(c, (c % 2 == 1 && c < 2 * columns) ? 1 : 0);
  }
}

//-----------------------------------------------------------------------------
void pqMaterialNodesPropertyWidget::resizeEvent(QResizeEvent* event)
{
  // Two label/editor pairs per row where they fit (compact), one in the
  // narrow default Properties panel (no horizontal scrolling).
  auto& internals = *this->Internals;
  int pair = 0;
  for (const auto& row : internals.Rows)
  {
    pair = std::max(pair, row.first->sizeHint().width());
  }
  int editor = 0;
  for (const auto& row : internals.Rows)
  {
    editor = std::max(editor, row.second->minimumSizeHint().width());
  }
  const int spacing = std::max(0, internals.Grid->horizontalSpacing());
  pair += editor + spacing;
  const int available = this->contentsRect().width() - 2 * pqPropertiesPanel::suggestedMargin();
  this->layoutEditors(available >= 2 * pair + spacing ? 2 : 1);
  this->Superclass::resizeEvent(event);
  internals.elideNotice();
}
