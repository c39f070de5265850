/**
 * @class   pqMaterialNodesPropertyWidget
 * @brief   Properties-panel editor for the "MaterialNodes" property of the
 *          Multi-Material Volume representation.
 *
 * MaterialNodes is a flat list, 13 numbers per node: the data value followed
 * by the 9 material parameters of mmv::MaterialParameterTable (lists of 9,
 * from before emission, are read with e = 0; lists of 8, from before
 * anisotropy, with g = 0 and e = 0). The widget shows
 * the nodes on a track spanning the data range, over the representation's
 * scalar opacity curve:
 *
 * - click on empty space adds a node (parameters interpolated from its
 *   neighbours, as vtkMaterialTransferFunction evaluates them),
 * - dragging a node moves its value (it stays between its neighbours),
 * - Delete/Backspace removes the selected node, Left/Right select another.
 *
 * Below the track, spin boxes edit the selected node, and a preset chooser
 * (vtkMaterialLibrary) applies a preset to the selected node or, with none
 * selected, to the whole range (the MaterialPreset property when the proxy
 * has one, otherwise two nodes at the ends of the range).
 *
 * All edits go through pqPropertyLinks (the "materialNodes" and
 * "materialPreset" Qt properties), so they take part in ParaView's
 * apply/undo/redo, Python trace and state files like any other property.
 *
 * The nodes and every edit of them are a mmv::MaterialNodeModel (no Qt); the
 * track is a pqMaterialNodesTrack; this class is the property plumbing and
 * the editors.
 *
 * Set PARAVIEW_LOG_APPLICATION_VERBOSITY=INFO to have the widget log its
 * creation and edits (the GUI test relies on this).
 */
#ifndef pqMaterialNodesPropertyWidget_h
#define pqMaterialNodesPropertyWidget_h

#include "pqPropertyWidget.h"

#include <QList>
#include <QScopedPointer>
#include <QString>
#include <QVariant>

class QHBoxLayout;
class QResizeEvent;

class pqMaterialNodesPropertyWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;

  Q_PROPERTY(QList<QVariant> materialNodes READ materialNodes WRITE setMaterialNodes NOTIFY
      materialNodesChanged)
  Q_PROPERTY(
    QString materialPreset READ materialPreset WRITE setMaterialPreset NOTIFY materialPresetChanged)
  // Read-only views for tests (QtTesting's <pqcheck> compares Qt properties).
  Q_PROPERTY(int nodeCount READ nodeCount)
  Q_PROPERTY(int currentNode READ currentNode WRITE setCurrentNode)
  Q_PROPERTY(QString nodesText READ nodesText)

public:
  pqMaterialNodesPropertyWidget(
    vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent = nullptr);
  ~pqMaterialNodesPropertyWidget() override;

  /// The nodes in the property's flat layout (13 numbers per node, sorted by value).
  QList<QVariant> materialNodes() const;
  /// Value of the proxy's MaterialPreset property as last set through the widget.
  QString materialPreset() const;

  int nodeCount() const;
  /// Index of the selected node, -1 when none is selected.
  int currentNode() const;
  /// The nodes as text, one "value: p0 p1 ... p6" line per node.
  QString nodesText() const;

  /// Data range the track spans (data range, widened to include the nodes).
  void trackRange(double range[2]) const;

public Q_SLOTS: // NOLINT(readability-redundant-access-specifiers)
  void setMaterialNodes(const QList<QVariant>& values);
  void setMaterialPreset(const QString& name);
  void setCurrentNode(int index);
  /// Adds a node at `value`; returns its index (an existing node there is selected).
  int addNode(double value);
  void removeCurrentNode();
  /// Applies a preset of vtkMaterialLibrary to the selection (see class docs).
  void applyPreset(const QString& name);

Q_SIGNALS:
  void materialNodesChanged();
  void materialPresetChanged();

protected:
  void resizeEvent(QResizeEvent* event) override;

private Q_SLOTS:
  void onParameterEdited();
  void onValueEdited();
  void onPresetActivated(int index);
  /// Re-reads the data range and the opacity function (data or colouring changed).
  void updateContext();

private: // NOLINT(readability-redundant-access-specifiers)
  Q_DISABLE_COPY(pqMaterialNodesPropertyWidget)

  friend class pqMaterialNodesTrack;
  class pqInternals;
  QScopedPointer<pqInternals> Internals;

  /// Inserts a node at `value` without committing; returns its index.
  /// `changed` tells whether the nodes changed (with a preset showing, they
  /// become the preset's plus the new one: the count may stay the same).
  int insertNode(double value, bool* changed = nullptr);
  /// Pushes the nodes to the property (one undoable change).
  void commitNodes();
  /// Moves node `index` to `value`, kept strictly between its neighbours.
  void moveNode(int index, double value, bool commit);
  /// Shows the selected node in the editors.
  void updateEditors();
  /// Places the editors in `columns` label/editor pairs per row.
  void layoutEditors(int columns);
  /// The preset chooser, the selection status and the remove button: one row.
  QHBoxLayout* createSelectionRow();
  /// The selected node's value and parameter editors, in a grid not yet laid out.
  void createEditors();
};

#endif
